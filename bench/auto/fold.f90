! AUTO-07p problem (IPS = -1): the period-3 orbits of the logistic map as
! fixed points of its third iterate, continued in r from r = 3.832 (where
! slipcont starts too) down to the fold at r = 1 + 2 sqrt 2
! (run_compare.py).  PVLS as in logistic3.f90: PAR(5) = r - (1 + 2 sqrt 2).
SUBROUTINE FUNC(NDIM, U, ICP, PAR, IJAC, F, DFDU, DFDP)
  IMPLICIT NONE
  INTEGER, INTENT(IN) :: NDIM, ICP(*), IJAC
  DOUBLE PRECISION, INTENT(IN) :: U(NDIM), PAR(*)
  DOUBLE PRECISION, INTENT(OUT) :: F(NDIM)
  DOUBLE PRECISION, INTENT(INOUT) :: DFDU(NDIM, NDIM), DFDP(NDIM, *)
  DOUBLE PRECISION :: X, DX, DR
  INTEGER :: I
  X = U(1)
  DX = 1   ! d x_k / d x_0
  DR = 0   ! d x_k / d r
  DO I = 1, 3
    DR = X * (1 - X) + PAR(1) * (1 - 2 * X) * DR
    DX = PAR(1) * (1 - 2 * X) * DX
    X = PAR(1) * X * (1 - X)
  END DO
  F(1) = X
  IF (IJAC == 0) RETURN
  DFDU(1, 1) = DX
  IF (IJAC == 1) RETURN
  DFDP(1, 1) = DR
END SUBROUTINE FUNC

SUBROUTINE STPNT(NDIM, U, PAR, T)
  IMPLICIT NONE
  INTEGER, INTENT(IN) :: NDIM
  DOUBLE PRECISION, INTENT(INOUT) :: U(NDIM), PAR(*)
  DOUBLE PRECISION, INTENT(IN) :: T
  DOUBLE PRECISION :: F(1), DFDU(1, 1), DFDP(1, 1)
  INTEGER :: ICP(1), K
  PAR(1) = 3.832D0
  U(1) = 0.1494D0
  ! A point of the stable period-3 orbit: Newton on f^3(x) - x.
  DO K = 1, 20
    CALL FUNC(NDIM, U, ICP, PAR, 1, F, DFDU, DFDP)
    U(1) = U(1) - (F(1) - U(1)) / (DFDU(1, 1) - 1)
  END DO
END SUBROUTINE STPNT

SUBROUTINE PVLS(NDIM, U, PAR)
  IMPLICIT NONE
  INTEGER, INTENT(IN) :: NDIM
  DOUBLE PRECISION, INTENT(IN) :: U(NDIM)
  DOUBLE PRECISION, INTENT(INOUT) :: PAR(*)
  PAR(2) = PAR(1) - 3D0
  PAR(3) = PAR(1) - (1 + SQRT(6D0))
  PAR(4) = PAR(1) - 3.5440903595519229D0
  PAR(5) = PAR(1) - (1 + 2 * SQRT(2D0))
END SUBROUTINE PVLS

SUBROUTINE BCND
END SUBROUTINE BCND

SUBROUTINE ICND
END SUBROUTINE ICND

SUBROUTINE FOPT
END SUBROUTINE FOPT
