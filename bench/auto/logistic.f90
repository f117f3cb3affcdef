! AUTO-07p problem (IPS = -1, fixed points of a map): the logistic map
! x -> r x (1 - x), as slipcont's model "logistic".  Continued in r from
! r = 2.8; the period-2 and period-4 branches by switching at the flips
! (ISW = -1, run_auto.sh).  PVLS stores r minus the exact special points
! in PAR(2..5), so that fort.7 shows the location error with its own 11
! significant digits instead of r rounded to 11 digits.
SUBROUTINE FUNC(NDIM, U, ICP, PAR, IJAC, F, DFDU, DFDP)
  IMPLICIT NONE
  INTEGER, INTENT(IN) :: NDIM, ICP(*), IJAC
  DOUBLE PRECISION, INTENT(IN) :: U(NDIM), PAR(*)
  DOUBLE PRECISION, INTENT(OUT) :: F(NDIM)
  DOUBLE PRECISION, INTENT(INOUT) :: DFDU(NDIM, NDIM), DFDP(NDIM, *)
  F(1) = PAR(1) * U(1) * (1 - U(1))
  IF (IJAC == 0) RETURN
  DFDU(1, 1) = PAR(1) * (1 - 2 * U(1))
  IF (IJAC == 1) RETURN
  DFDP(1, 1) = U(1) * (1 - U(1))
END SUBROUTINE FUNC

SUBROUTINE STPNT(NDIM, U, PAR, T)
  IMPLICIT NONE
  INTEGER, INTENT(IN) :: NDIM
  DOUBLE PRECISION, INTENT(INOUT) :: U(NDIM), PAR(*)
  DOUBLE PRECISION, INTENT(IN) :: T
  PAR(1) = 2.8D0
  U(1) = 1 - 1 / PAR(1) ! the fixed point, exactly
END SUBROUTINE STPNT

SUBROUTINE PVLS(NDIM, U, PAR)
  IMPLICIT NONE
  INTEGER, INTENT(IN) :: NDIM
  DOUBLE PRECISION, INTENT(IN) :: U(NDIM)
  DOUBLE PRECISION, INTENT(INOUT) :: PAR(*)
  PAR(2) = PAR(1) - 3D0                    ! flip of the fixed point
  PAR(3) = PAR(1) - (1 + SQRT(6D0))        ! flip of the period-2 orbit
  PAR(4) = PAR(1) - 3.5440903595519229D0   ! flip of the period-4 orbit
  PAR(5) = PAR(1) - (1 + 2 * SQRT(2D0))    ! fold of the period-3 orbit
END SUBROUTINE PVLS

SUBROUTINE BCND
END SUBROUTINE BCND

SUBROUTINE ICND
END SUBROUTINE ICND

SUBROUTINE FOPT
END SUBROUTINE FOPT
