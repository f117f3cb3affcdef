! AUTO-07p problem (IPS = -1): the cubic map x -> x + mu1 + mu2 x - x^3,
! as slipcont's model "cubic", for its fold curve 27 mu1^2 = 4 mu2^3 and
! the cusp at the origin (run_compare.py).  The start is the fixed point
! at mu1 = 0.45, mu2 = 1.2, a little before the fold at mu1 = 2 (0.4)^1.5
! (slipcont starts from a guess as far from its fold).  PVLS stores, with
! full precision, the relative violation (27 mu1^2 - 4 mu2^3)/(1 + 27 mu1^2)
! in PAR(3) and max(|mu1|, |mu2|, |x|), the distance from the cusp, in
! PAR(4).
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
  PAR(1) = 0.45D0
  PAR(2) = 1.2D0
  U(1) = -1D0
  ! The fixed point of the lower branch: Newton on mu1 + mu2 x - x^3 = 0.
  DO K = 1, 30
    U(1) = U(1) - (PAR(1) + PAR(2) * U(1) - U(1)**3) / (PAR(2) - 3 * U(1)**2)
  END DO
END SUBROUTINE STPNT

SUBROUTINE PVLS(NDIM, U, PAR)
  IMPLICIT NONE
  INTEGER, INTENT(IN) :: NDIM
  DOUBLE PRECISION, INTENT(IN) :: U(NDIM)
  DOUBLE PRECISION, INTENT(INOUT) :: PAR(*)
  PAR(3) = (27 * PAR(1)**2 - 4 * PAR(2)**3) / (1 + 27 * PAR(1)**2)
  PAR(4) = MAX(ABS(PAR(1)), ABS(PAR(2)), ABS(U(1)))
END SUBROUTINE PVLS

SUBROUTINE BCND
END SUBROUTINE BCND

SUBROUTINE ICND
END SUBROUTINE ICND

SUBROUTINE FOPT
END SUBROUTINE FOPT
