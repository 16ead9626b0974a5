!> The intrados shapes of a &bridge span, as closed forms: the point and the outward unit
!> normal at an arc length along the intrados from the left springing, the whole length,
!> and where the springing joint reaches. Both the validation of &bridge (the refusals that
!> follow from the values alone: a skewback too narrow, spans that do not meet their pier)
!> and the builder (src/assembly/bridge.f90) take their geometry from here, so the two
!> cannot disagree. docs/bridges.md, "Shapes".
!>
!> Local frame of one span: the left intrados springing at (0, 0), the right one at
!> (span, 0), y up. Shapes (span L, rise r):
!>
!> - segmental: a circular arc through both springings and the crown (L/2, r), radius
!>   R = (L^2/4 + r^2) / (2 r), 0 < r <= L/2;
!> - semicircular: R = L/2 (r = L/2);
!> - elliptical: semi-axes L/2 and r about (L/2, 0), any r > 0;
!> - three-centred: two haunch arcs of 60 degrees each (centres on the springing line,
!>   vertical at the springings) and a crown arc of 60 degrees, tangent where they meet;
!>   their radii follow from L and r, which needs (1 - (cos 60 + sin 60 - 1)/cos 60) L/2
!>   < r < L/2 (0.134 L < r < 0.5 L; below, the haunch radius would be negative);
!> - pointed: two arcs of equal radius R = (r^2 + L^2/4) / L, centred on the springing line
!>   (each halfway's centre on the other side of midspan), meeting at the apex (L/2, r);
!>   r >= L/2 (r = L sqrt(3)/2: the equilateral arch, R = L);
!> - parabolic: y = 4 r x (L - x) / L^2.
module voussoir_bridge_shape
  use voussoir_kinds, only: dp, pi
  implicit none
  private

  public :: intrados_t, intrados_init, intrados_length, intrados_at, springing_reach, crown_extrados_m
  public :: shape_segmental, shape_semicircular, shape_elliptical, shape_three_centred, shape_pointed, &
            shape_parabolic, shape_names, three_centred_min_rise_ratio

  character(len=*), parameter :: shape_segmental = 'segmental', shape_semicircular = 'semicircular', &
    shape_elliptical = 'elliptical', shape_three_centred = 'three-centred', shape_pointed = 'pointed', &
    shape_parabolic = 'parabolic'
  character(len=16), parameter :: shape_names(6) = [character(len=16) :: shape_segmental, shape_semicircular, &
    shape_elliptical, shape_three_centred, shape_pointed, shape_parabolic]

  !> The haunch arcs of a three-centred arch turn through this angle (and the crown arc
  !> through pi - 2 times it).
  real(dp), parameter :: haunch_rad = pi/3.0_dp
  !> A three-centred arch of 60-degree haunches needs rise/span above this (its haunch
  !> radius shrinks to zero there) and below 1/2.
  real(dp), parameter :: three_centred_min_rise_ratio = &
    0.5_dp*(1.0_dp - (cos(haunch_rad) + sin(haunch_rad) - 1.0_dp)/cos(haunch_rad))

  !> One span's intrados: its shape and the constants of its closed form.
  type :: intrados_t
    character(len=16) :: shape = shape_segmental
    real(dp) :: span_m = 0.0_dp, rise_m = 0.0_dp
    real(dp) :: radius_m = 0.0_dp      !! segmental, semicircular, pointed: R; three-centred: the haunch radius
    real(dp) :: crown_radius_m = 0.0_dp !! three-centred: the crown arc's radius
    real(dp) :: centre_y_m = 0.0_dp    !! segmental: the circle's centre's y; three-centred: the crown centre's
    real(dp) :: half_angle_rad = 0.0_dp !! segmental: the angle of a springing from the vertical
    real(dp) :: length_m = 0.0_dp      !! the whole arc length
  end type intrados_t

contains

  !> The intrados of `shape` over `span_m` with `rise_m` (ranges checked by the caller).
  pure function intrados_init(shape, span_m, rise_m) result(c)
    character(len=*), intent(in) :: shape
    real(dp), intent(in) :: span_m, rise_m
    type(intrados_t) :: c
    real(dp) :: d
    c%shape = shape
    c%span_m = span_m
    c%rise_m = rise_m
    select case (shape)
    case (shape_segmental, shape_semicircular)
      if (shape == shape_semicircular) c%rise_m = 0.5_dp*span_m
      c%radius_m = (0.25_dp*span_m**2 + c%rise_m**2)/(2.0_dp*c%rise_m)
      if (shape == shape_semicircular) c%radius_m = 0.5_dp*span_m
      c%centre_y_m = c%rise_m - c%radius_m
      c%half_angle_rad = atan2(0.5_dp*span_m, c%radius_m - c%rise_m)
      c%length_m = 2.0_dp*c%radius_m*c%half_angle_rad
    case (shape_pointed)
      c%radius_m = (rise_m**2 + 0.25_dp*span_m**2)/span_m
      c%half_angle_rad = pi - acos((0.5_dp*span_m - c%radius_m)/c%radius_m)   ! each half's sweep
      c%length_m = 2.0_dp*c%radius_m*c%half_angle_rad
    case (shape_three_centred)
      d = (0.5_dp*span_m - rise_m)/(cos(haunch_rad) + sin(haunch_rad) - 1.0_dp)
      c%radius_m = 0.5_dp*span_m - d*cos(haunch_rad)
      c%crown_radius_m = c%radius_m + d
      c%centre_y_m = rise_m - c%crown_radius_m
      c%length_m = 2.0_dp*c%radius_m*haunch_rad + c%crown_radius_m*(pi - 2.0_dp*haunch_rad)
    case (shape_elliptical)
      c%length_m = ellipse_length(0.5_dp*span_m, rise_m, pi)
    case (shape_parabolic)
      c%length_m = parabola_length(c, span_m)
    end select
  end function intrados_init

  pure real(dp) function intrados_length(c)
    type(intrados_t), intent(in) :: c
    intrados_length = c%length_m
  end function intrados_length

  !> The point `p` [m] of the intrados at arc length `s_m` from the left springing and the
  !> unit normal `n` there, pointing out of the opening (into the ring). At the apex of a
  !> pointed arch, where its two arcs meet at an angle, the normal is vertical.
  pure subroutine intrados_at(c, s_m, p, n)
    type(intrados_t), intent(in) :: c
    real(dp), intent(in) :: s_m
    real(dp), intent(out) :: p(2), n(2)
    real(dp) :: phi, s, half, tau, x, slope
    logical :: right
    s = min(max(s_m, 0.0_dp), c%length_m)
    select case (c%shape)
    case (shape_segmental, shape_semicircular)
      phi = c%half_angle_rad - s/c%radius_m      ! from the vertical, positive to the left
      n = [-sin(phi), cos(phi)]
      p = [0.5_dp*c%span_m, c%centre_y_m] + c%radius_m*n
    case (shape_pointed)
      half = 0.5_dp*c%length_m
      right = s > half
      if (right) s = c%length_m - s
      phi = pi - s/c%radius_m                    ! from +x about the left half's centre (R, 0)
      n = [cos(phi), sin(phi)]
      p = [c%radius_m, 0.0_dp] + c%radius_m*n
      if (s == half) then
        p(1) = 0.5_dp*c%span_m
        n = [0.0_dp, 1.0_dp]
      end if
      if (right) then
        p(1) = c%span_m - p(1)
        n(1) = -n(1)
      end if
    case (shape_three_centred)
      half = 0.5_dp*c%length_m
      right = s > half
      if (right) s = c%length_m - s
      if (s <= c%radius_m*haunch_rad) then
        phi = pi - s/c%radius_m
        n = [cos(phi), sin(phi)]
        p = [c%radius_m, 0.0_dp] + c%radius_m*n
      else
        phi = pi - haunch_rad - (s - c%radius_m*haunch_rad)/c%crown_radius_m
        n = [cos(phi), sin(phi)]
        p = [0.5_dp*c%span_m, c%centre_y_m] + c%crown_radius_m*n
      end if
      if (s == half) p(1) = 0.5_dp*c%span_m
      if (right) then
        p(1) = c%span_m - p(1)
        n(1) = -n(1)
      end if
    case (shape_elliptical)
      tau = ellipse_parameter(0.5_dp*c%span_m, c%rise_m, s)
      p = [0.5_dp*c%span_m*(1.0_dp - cos(tau)), c%rise_m*sin(tau)]
      n = [-c%rise_m*cos(tau), 0.5_dp*c%span_m*sin(tau)]
      n = n/norm2(n)
    case (shape_parabolic)
      x = parabola_x(c, s)
      slope = 4.0_dp*c%rise_m*(c%span_m - 2.0_dp*x)/c%span_m**2
      p = [x, 4.0_dp*c%rise_m*x*(c%span_m - x)/c%span_m**2]
      n = [-slope, 1.0_dp]/sqrt(1.0_dp + slope**2)
    case default
      p = 0.0_dp
      n = [0.0_dp, 1.0_dp]
    end select
  end subroutine intrados_at

  !> How far the left springing joint of a ring `thickness_m` deep reaches [m]: back from
  !> the intrados springing (horizontally, `back_m` >= 0) and up (`up_m`). The right
  !> springing mirrors it.
  pure subroutine springing_reach(c, thickness_m, back_m, up_m)
    type(intrados_t), intent(in) :: c
    real(dp), intent(in) :: thickness_m
    real(dp), intent(out) :: back_m, up_m
    real(dp) :: p(2), n(2)
    call intrados_at(c, 0.0_dp, p, n)
    back_m = -thickness_m*n(1)
    up_m = thickness_m*n(2)
    if (abs(up_m) <= 1.0e-12_dp*thickness_m) up_m = 0.0_dp   ! a horizontal springing joint
  end subroutine springing_reach

  !> The extrados apex of a pointed arch [m above the springings]: where the two extrados
  !> arcs (radius R + t about the same centres) meet.
  pure real(dp) function crown_extrados_m(c, thickness_m)
    type(intrados_t), intent(in) :: c
    real(dp), intent(in) :: thickness_m
    crown_extrados_m = sqrt((c%radius_m + thickness_m)**2 - (c%radius_m - 0.5_dp*c%span_m)**2)
  end function crown_extrados_m

  !> Arc length of the ellipse (a cos, b sin) from tau = 0 to `tau` [m]: Gauss-Legendre,
  !> 5 points on each of 400 panels (the integrand is smooth; 1e-15 relative).
  pure real(dp) function ellipse_length(a, b, tau)
    real(dp), intent(in) :: a, b, tau
    real(dp), parameter :: x5(5) = [-0.9061798459386640_dp, -0.5384693101056831_dp, 0.0_dp, &
                                    0.5384693101056831_dp, 0.9061798459386640_dp]
    real(dp), parameter :: w5(5) = [0.2369268850561891_dp, 0.4786286704993665_dp, 0.5688888888888889_dp, &
                                    0.4786286704993665_dp, 0.2369268850561891_dp]
    integer, parameter :: panels = 400
    real(dp) :: h, mid, t
    integer :: k, q
    ellipse_length = 0.0_dp
    h = tau/panels
    do k = 1, panels
      mid = (k - 0.5_dp)*h
      do q = 1, 5
        t = mid + 0.5_dp*h*x5(q)
        ellipse_length = ellipse_length + 0.5_dp*h*w5(q)*sqrt((a*sin(t))**2 + (b*cos(t))**2)
      end do
    end do
  end function ellipse_length

  !> The parameter tau of the point at arc length `s_m` on the ellipse (bisection to round-off).
  pure real(dp) function ellipse_parameter(a, b, s_m) result(tau)
    real(dp), intent(in) :: a, b, s_m
    real(dp) :: lo, hi
    integer :: k
    lo = 0.0_dp
    hi = pi
    do k = 1, 60
      tau = 0.5_dp*(lo + hi)
      if (ellipse_length(a, b, tau) < s_m) then
        lo = tau
      else
        hi = tau
      end if
    end do
    tau = 0.5_dp*(lo + hi)
  end function ellipse_parameter

  !> Arc length of the parabola from x = 0 to `x` [m], closed form: with u = y'(x),
  !> s = (F(u(0)) - F(u(x))) / (2 k), F(u) = (u sqrt(1 + u^2) + asinh(u)) / 2, k = 4 r / L^2.
  pure real(dp) function parabola_length(c, x)
    type(intrados_t), intent(in) :: c
    real(dp), intent(in) :: x
    real(dp) :: k
    k = 4.0_dp*c%rise_m/c%span_m**2
    parabola_length = (big_f(k*c%span_m) - big_f(k*(c%span_m - 2.0_dp*x)))/(2.0_dp*k)
  contains
    pure real(dp) function big_f(u)
      real(dp), intent(in) :: u
      big_f = 0.5_dp*(u*sqrt(1.0_dp + u**2) + asinh(u))
    end function big_f
  end function parabola_length

  !> The x of the point at arc length `s_m` along the parabola (bisection to round-off).
  pure real(dp) function parabola_x(c, s_m) result(x)
    type(intrados_t), intent(in) :: c
    real(dp), intent(in) :: s_m
    real(dp) :: lo, hi
    integer :: k
    lo = 0.0_dp
    hi = c%span_m
    do k = 1, 60
      x = 0.5_dp*(lo + hi)
      if (parabola_length(c, x) < s_m) then
        lo = x
      else
        hi = x
      end if
    end do
    x = 0.5_dp*(lo + hi)
  end function parabola_x

end module voussoir_bridge_shape
