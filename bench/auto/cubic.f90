! AUTO-07p problem (IPS = -1): the cubic map x -> x + mu1 + mu2 x - x^3,
! as slipcont's model "cubic", at mu2 = 1/2, continued in mu1 from -1 to
! 1 along the S-shaped branch of fixed points mu1 = x^3 - mu2 x: flips
! where f' = 1 + mu2 - 3 x^2 = -1 (x = -+sqrt(5/6), mu1 = -+sqrt(5/6)/3),
! folds where f' = 1 (x = -+1/sqrt 6, mu1 = +-1/(3 sqrt 6)).  PVLS stores
! mu1 minus each exact value in PAR(3..6) (see logistic.f90).
SUBROUTINE FUNC(NDIM, U, ICP, PAR, IJAC, F, DFDU, DFDP)
  IMPLICIT NONE
  INTEGER, INTENT(IN) :: NDIM, ICP(*), IJAC
  DOUBLE PRECISION, INTENT(IN) :: U(NDIM), PAR(*)
  DOUBLE PRECISION, INTENT(OUT) :: F(NDIM)
  DOUBLE PRECISION, INTENT(INOUT) :: DFDU(NDIM, NDIM), DFDP(NDIM, *)
  F(1) = U(1) + PAR(1) + PAR(2) * U(1) - U(1)**3
  IF (IJAC == 0) RETURN
  DFDU(1, 1) = 1 + PAR(2) - 3 * U(1)**2
  IF (IJAC == 1) RETURN
  DFDP(1, 1) = 1
  DFDP(1, 2) = U(1)
END SUBROUTINE FUNC

SUBROUTINE STPNT(NDIM, U, PAR, T)
  IMPLICIT NONE
  INTEGER, INTENT(IN) :: NDIM
  DOUBLE PRECISION, INTENT(INOUT) :: U(NDIM), PAR(*)
  DOUBLE PRECISION, INTENT(IN) :: T
  INTEGER :: K
  PAR(1) = -1D0
  PAR(2) = 0.5D0
  U(1) = -1.165D0
  ! The fixed point: Newton on mu1 + mu2 x - x^3 = 0.
  DO K = 1, 20
    U(1) = U(1) - (PAR(1) + PAR(2) * U(1) - U(1)**3) / (PAR(2) - 3 * U(1)**2)
  END DO
END SUBROUTINE STPNT

SUBROUTINE PVLS(NDIM, U, PAR)
  IMPLICIT NONE
  INTEGER, INTENT(IN) :: NDIM
  DOUBLE PRECISION, INTENT(IN) :: U(NDIM)
  DOUBLE PRECISION, INTENT(INOUT) :: PAR(*)
  PAR(3) = PAR(1) + SQRT(5D0 / 6) / 3         ! flip at x = -sqrt(5/6)
  PAR(4) = PAR(1) - 1 / (3 * SQRT(6D0))       ! fold at x = -1/sqrt 6
  PAR(5) = PAR(1) + 1 / (3 * SQRT(6D0))       ! fold at x = +1/sqrt 6
  PAR(6) = PAR(1) - SQRT(5D0 / 6) / 3         ! flip at x = +sqrt(5/6)
END SUBROUTINE PVLS

SUBROUTINE BCND
END SUBROUTINE BCND

SUBROUTINE ICND
END SUBROUTINE ICND

SUBROUTINE FOPT
END SUBROUTINE FOPT
