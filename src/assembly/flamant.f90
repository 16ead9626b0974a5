!> Flamant's solution of Boussinesq's problem in plane strain: the vertical stress under a
!> line load P [N per the analysed width] on the surface of an elastic half-plane, at depth
!> z and horizontal offset u from the load, sigma_v = 2 P z^3 / (pi (u^2 + z^2)^2)
!> (Flamant 1892; Poulos and Davis 1974), and under a uniform strip load of P over a patch
!> of length p (q = P/p) by integrating the point solution across the patch. With
!> G(t) = atan(t) + t/(1 + t^2) and H(t) = t atan(t) (H' = G, G' = 2/(1 + t^2)^2):
!>   the stress of a point load      sigma_v = (P/(pi z)) G'(u/z),
!>   its integral over u from a to b  (P/pi) [G(b/z) - G(a/z)],
!>   the stress of a patch            (q/pi) [G((u + p/2)/z) - G((u - p/2)/z)],
!>   its integral from a to b          (q z/pi) [H((b + p/2)/z) - H((b - p/2)/z) - H((a + p/2)/z) + H((a - p/2)/z)].
!> Over the whole line (a -> -inf, b -> inf) each integral is P. docs/bridges.md,
!> "Boussinesq dispersion".
module voussoir_flamant
  use voussoir_kinds, only: dp, pi
  implicit none
  private
  public :: flamant_pressure, flamant_force

  !> A patch shorter than this fraction of the depth is taken as a point: the patch's
  !> closed form is a second difference that loses digits there, and the two differ by
  !> about (p/z)^2.
  real(dp), parameter :: point_patch_ratio = 1.0e-6_dp

contains

  !> The vertical stress [N/m per the width] at depth `z_m` > 0 and offset `u_m` from the
  !> centre of a load `load_n` spread uniformly over `patch_m` (0: a point).
  elemental real(dp) function flamant_pressure(load_n, patch_m, u_m, z_m) result(sigma)
    real(dp), intent(in) :: load_n, patch_m, u_m, z_m
    real(dp) :: h
    if (patch_m <= point_patch_ratio*z_m) then
      sigma = 2.0_dp*load_n*z_m**3/(pi*(u_m**2 + z_m**2)**2)
    else
      h = 0.5_dp*patch_m
      sigma = load_n/(pi*patch_m)*(g((u_m + h)/z_m) - g((u_m - h)/z_m))
    end if
  end function flamant_pressure

  !> The vertical force [N] that stress carries across the horizontal interval from offset
  !> `a_m` to `b_m` (a < b) at depth `z_m` > 0.
  elemental real(dp) function flamant_force(load_n, patch_m, a_m, b_m, z_m) result(force)
    real(dp), intent(in) :: load_n, patch_m, a_m, b_m, z_m
    real(dp) :: h
    if (patch_m <= point_patch_ratio*z_m) then
      force = load_n/pi*(g(b_m/z_m) - g(a_m/z_m))
    else
      h = 0.5_dp*patch_m
      force = load_n*z_m/(pi*patch_m)*(hh((b_m + h)/z_m) - hh((b_m - h)/z_m) - hh((a_m + h)/z_m) + hh((a_m - h)/z_m))
    end if
  end function flamant_force

  elemental real(dp) function g(t)
    real(dp), intent(in) :: t
    g = atan(t) + t/(1.0_dp + t*t)
  end function g

  elemental real(dp) function hh(t)
    real(dp), intent(in) :: t
    hh = t*atan(t)
  end function hh

end module voussoir_flamant
