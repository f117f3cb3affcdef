! AUTO-07p problem (IPS = -1, fixed points of a map): the logistic map
! x -> r x (1 - x), as slipcont's model "logistic", continued in r from
! r = 2.8 and switched at each flip (ISW = -1) onto the period-doubled
! branch (run_compare.py).  PVLS stores r minus each flip r_1 .. r_6 of
! the cascade (50-digit values rounded to double, tests/test_continuation.c)
! in PAR(2..7): fort.7 then shows each flip's error with 11 significant
! digits of its own, where r itself is written to 11 digits.
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
  U(1) = 1 - 1 / PAR(1) ! the fixed point
END SUBROUTINE STPNT

SUBROUTINE PVLS(NDIM, U, PAR)
  IMPLICIT NONE
  INTEGER, INTENT(IN) :: NDIM
  DOUBLE PRECISION, INTENT(IN) :: U(NDIM)
  DOUBLE PRECISION, INTENT(INOUT) :: PAR(*)
  PAR(2) = PAR(1) - 3D0
  PAR(3) = PAR(1) - 3.44948974278317809819728407471D0
  PAR(4) = PAR(1) - 3.5440903595519228536159659866D0
  PAR(5) = PAR(1) - 3.56440726609543259777355758653D0
  PAR(6) = PAR(1) - 3.56875941954382643129821028003D0
  PAR(7) = PAR(1) - 3.5696916098013967142882687063D0
END SUBROUTINE PVLS

SUBROUTINE BCND
END SUBROUTINE BCND

SUBROUTINE ICND
END SUBROUTINE ICND

SUBROUTINE FOPT
END SUBROUTINE FOPT
