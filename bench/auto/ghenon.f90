! AUTO-07p problem (IPS = -1, fixed points of a map): the generalized
! Henon map (x, y) -> (y, alpha - beta x - y^2 + R x y), as slipcont's
! model "ghenon" (PAR(1) = alpha, PAR(2) = beta, PAR(3) = R), for the
! comparison of docs/performance.md, "Beside AUTO-07p: ghenon"
! (run_ghenon.py).  The start is the fixed point x = y = s = -5.64 at
! alpha = 3.5, beta = 1.2, R = 0.5 (the lower root of
! (1 - R) s^2 + (1 + beta) s = alpha), where slipcont starts too.
!
! Its fixed points are x = y = s with (1 - R) s^2 + (1 + beta) s = alpha;
! the Jacobian there has trace (R - 2) s and determinant beta - R s, so
! (docs/maps.md, "The ghenon atlas"):
!   fold (LP, 1 - tr + det = 0): alpha = (1 + beta)^2 / (4 (R - 1));
!   flip (PD, 1 + tr + det = 0): alpha = (3 - R) (1 + beta)^2 / 4;
!   NS (TR, det = 1, |tr| < 2):  s = (beta - 1) / R,
!                                alpha = (1 - R) s^2 + (1 + beta) s;
!   R1 (tr = 2, det = 1):  s =  2 / (R - 2), beta = 1 + R s;
!   R2 (tr = -2, det = 1): s = -2 / (R - 2), beta = 1 + R s;
!   R3 (tr = -1, det = 1): s = -1 / (R - 2), beta = 1 + R s;
!   R4 (tr = 0, det = 1):  s = 0, beta = 1, alpha = 0;
!   LPPD (tr = 0, det = -1): s = 0, beta = -1, alpha = 0.
! PVLS stores, computed inside AUTO in double precision (AUTO writes its
! values with 11 significant digits; these errors keep their own):
!   PAR(4), PAR(5), PAR(6): alpha minus the fold's, flip's and NS's alpha
!     at this beta;
!   PAR(7): the fixed-point residual max |f(x, y) - (x, y)|;
!   PAR(8): max(|x - s|, |y - s|), s the fixed point on the NS curve at
!     this beta;
!   PAR(13) .. PAR(17): the distance max(|alpha - alpha*|, |beta - beta*|)
!     from R1, R2, R3, R4 and LPPD.
! (PAR(11) and PAR(12) are AUTO's own for maps: the iterate and the NS
! angle.)
SUBROUTINE FUNC(NDIM, U, ICP, PAR, IJAC, F, DFDU, DFDP)
  IMPLICIT NONE
  INTEGER, INTENT(IN) :: NDIM, ICP(*), IJAC
  DOUBLE PRECISION, INTENT(IN) :: U(NDIM), PAR(*)
  DOUBLE PRECISION, INTENT(OUT) :: F(NDIM)
  DOUBLE PRECISION, INTENT(INOUT) :: DFDU(NDIM, NDIM), DFDP(NDIM, *)
  F(1) = U(2)
  F(2) = PAR(1) - PAR(2) * U(1) - U(2)**2 + PAR(3) * U(1) * U(2)
  IF (IJAC == 0) RETURN
  DFDU(1, 1) = 0
  DFDU(1, 2) = 1
  DFDU(2, 1) = -PAR(2) + PAR(3) * U(2)
  DFDU(2, 2) = -2 * U(2) + PAR(3) * U(1)
  IF (IJAC == 1) RETURN
  DFDP(1, 1) = 0
  DFDP(1, 2) = 0
  DFDP(1, 3) = 0
  DFDP(2, 1) = 1
  DFDP(2, 2) = -U(1)
  DFDP(2, 3) = U(1) * U(2)
END SUBROUTINE FUNC

SUBROUTINE STPNT(NDIM, U, PAR, T)
  IMPLICIT NONE
  INTEGER, INTENT(IN) :: NDIM
  DOUBLE PRECISION, INTENT(INOUT) :: U(NDIM), PAR(*)
  DOUBLE PRECISION, INTENT(IN) :: T
  DOUBLE PRECISION :: S
  PAR(1) = 3.5D0
  PAR(2) = 1.2D0
  PAR(3) = 0.5D0
  ! the root s < -(1 + beta) / (2 (1 - R)) of the fixed-point equation
  S = (-(1 + PAR(2)) - SQRT((1 + PAR(2))**2 + 4 * (1 - PAR(3)) * PAR(1))) &
      / (2 * (1 - PAR(3)))
  U(1) = S
  U(2) = S
END SUBROUTINE STPNT

! max(|alpha - A|, |beta - B|) for the point with fixed point S and
! beta = B on the curve of fixed points (alpha from S and B).
DOUBLE PRECISION FUNCTION DIST2(PAR, S, B)
  IMPLICIT NONE
  DOUBLE PRECISION, INTENT(IN) :: PAR(*), S, B
  DIST2 = MAX(ABS(PAR(1) - ((1 - PAR(3)) * S**2 + (1 + B) * S)), &
              ABS(PAR(2) - B))
END FUNCTION DIST2

SUBROUTINE PVLS(NDIM, U, PAR)
  IMPLICIT NONE
  INTEGER, INTENT(IN) :: NDIM
  DOUBLE PRECISION, INTENT(IN) :: U(NDIM)
  DOUBLE PRECISION, INTENT(INOUT) :: PAR(*)
  DOUBLE PRECISION :: AL, BE, R, S, DIST2
  AL = PAR(1)
  BE = PAR(2)
  R = PAR(3)
  S = (BE - 1) / R
  PAR(4) = AL - (1 + BE)**2 / (4 * (R - 1))
  PAR(5) = AL - (3 - R) * (1 + BE)**2 / 4
  PAR(6) = AL - ((1 - R) * S**2 + (1 + BE) * S)
  PAR(7) = MAX(ABS(U(2) - U(1)), &
               ABS(AL - BE * U(1) - U(2)**2 + R * U(1) * U(2) - U(2)))
  PAR(8) = MAX(ABS(U(1) - S), ABS(U(2) - S))
  S = 2 / (R - 2)
  PAR(13) = DIST2(PAR, S, 1 + R * S)
  S = -2 / (R - 2)
  PAR(14) = DIST2(PAR, S, 1 + R * S)
  S = -1 / (R - 2)
  PAR(15) = DIST2(PAR, S, 1 + R * S)
  PAR(16) = DIST2(PAR, 0D0, 1D0)
  PAR(17) = DIST2(PAR, 0D0, -1D0)
END SUBROUTINE PVLS

SUBROUTINE BCND
END SUBROUTINE BCND

SUBROUTINE ICND
END SUBROUTINE ICND

SUBROUTINE FOPT
END SUBROUTINE FOPT
