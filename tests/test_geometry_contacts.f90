!> Unit checks of the geometry, the detection and the local Coulomb solve, each against
!> a hand computation.
program test_geometry_contacts
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use voussoir_kinds, only: dp, pi
  use voussoir_geometry, only: polygon_area, polygon_centroid, polygon_polar_moment, is_convex_ccw, &
                               overlap_depth, polygon_min_width
  use voussoir_assembly, only: assembly_t, build_arch
  use voussoir_contacts, only: polygon_contact
  use voussoir_nlgs, only: coulomb_local
  use voussoir_motion, only: motion_t, motion_afd, motion_ramp, motion_eval, motion_duration_s
  use voussoir_assert, only: assert_true, assert_close, assert_summary
  implicit none

  call polygons()
  call arch_geometry()
  call contacts()
  call local_solver()
  call afd_waveform()
  call motion_lead()
  call assert_summary()

contains

  subroutine polygons()
    real(dp) :: rect(2, 4), tri(2, 3), c(2), star(2, 5), nan_rect(2, 4)
    integer :: k
    ! 2 x 1 rectangle with a corner at (1, 1): area 2, centroid (2, 1.5),
    ! polar moment (a^2 + b^2) A / 12 = 5 * 2 / 12.
    rect = reshape([1.0_dp, 1.0_dp, 3.0_dp, 1.0_dp, 3.0_dp, 2.0_dp, 1.0_dp, 2.0_dp], [2, 4])
    call assert_close(polygon_area(rect), 2.0_dp, 'rectangle area [m2]', rtol=1.0e-14_dp)
    c = polygon_centroid(rect)
    call assert_close(c(1), 2.0_dp, 'rectangle centroid x [m]', rtol=1.0e-14_dp)
    call assert_close(c(2), 1.5_dp, 'rectangle centroid y [m]', rtol=1.0e-14_dp)
    call assert_close(polygon_polar_moment(rect), 10.0_dp/12.0_dp, 'rectangle polar moment [m4]', rtol=1.0e-14_dp)
    call assert_true(is_convex_ccw(rect), 'rectangle is convex ccw')
    call assert_true(.not. is_convex_ccw(rect(:, 4:1:-1)), 'clockwise rectangle is rejected')
    ! A pentagram (every second vertex of a regular pentagon) turns left at every vertex
    ! and has a positive area, but its edges cross: it goes round twice.
    do k = 0, 4
      star(:, k + 1) = [cos(4.0_dp*pi*k/5.0_dp), sin(4.0_dp*pi*k/5.0_dp)]
    end do
    call assert_true(polygon_area(star) > 0.0_dp, 'pentagram has a positive signed area')
    call assert_true(.not. is_convex_ccw(star), 'pentagram (edges crossing) is rejected')
    call assert_true(is_convex_ccw(star(:, [1, 4, 2, 5, 3])), 'regular pentagon is convex ccw')
    nan_rect = rect
    nan_rect(1, 3) = ieee_value(1.0_dp, ieee_quiet_nan)
    call assert_true(.not. is_convex_ccw(nan_rect), 'rectangle with a NaN vertex is rejected')
    ! Right triangle legs 3 and 4: area 6, centroid (1, 4/3).
    tri = reshape([0.0_dp, 0.0_dp, 3.0_dp, 0.0_dp, 0.0_dp, 4.0_dp], [2, 3])
    call assert_close(polygon_area(tri), 6.0_dp, 'triangle area [m2]', rtol=1.0e-14_dp)
    c = polygon_centroid(tri)
    call assert_close(c(1), 1.0_dp, 'triangle centroid x [m]', rtol=1.0e-14_dp)
    call assert_close(c(2), 4.0_dp/3.0_dp, 'triangle centroid y [m]', rtol=1.0e-14_dp)
    ! Widths: the rectangle's short side; the triangle's smallest altitude, 3 * 4 / 5.
    call assert_close(polygon_min_width(rect), 1.0_dp, 'rectangle min width [m]', rtol=1.0e-14_dp)
    call assert_close(polygon_min_width(tri), 2.4_dp, 'triangle min width [m]', rtol=1.0e-14_dp)
    ! Overlap: the rectangle shifted by (1.9, 0) overlaps it by 0.1 m; by (2, 0) it
    ! touches (0); by (0.5, 0.8) the shallowest axis is y, 0.2 m.
    call assert_close(overlap_depth(rect, rect + spread([1.9_dp, 0.0_dp], 2, 4)), 0.1_dp, &
                      'overlap of rectangles shifted by 1.9 m [m]', rtol=1.0e-12_dp)
    call assert_true(abs(overlap_depth(rect, rect + spread([2.0_dp, 0.0_dp], 2, 4))) < 1.0e-14_dp, &
                     'rectangles side by side touch (depth 0)')
    call assert_close(overlap_depth(rect, rect + spread([0.5_dp, 0.8_dp], 2, 4)), 0.2_dp, &
                      'overlap of rectangles shifted by (0.5, 0.8) m [m]', rtol=1.0e-12_dp)
    call assert_true(overlap_depth(rect, tri + spread([5.0_dp, 0.0_dp], 2, 3)) < 0.0_dp, &
                     'a triangle 2 m away does not overlap')
  end subroutine polygons

  subroutine arch_geometry()
    type(assembly_t) :: arch
    real(dp) :: area, expected
    integer :: j
    call build_arch(156.0_dp, 13, 0.508_dp, 0.071_dp, arch)
    call assert_true(arch%n_bodies == 15, 'arch of 13 voussoirs has 15 bodies')
    ! A voussoir with chord faces is a trapezoid: (chord_ext + chord_int)/2 * t cos(phi/2)
    ! with chords 2 r sin(phi/2).
    expected = 0.5_dp*(2*0.508_dp + 2*0.437_dp)*sin(6.0_dp*pi/180.0_dp)*0.071_dp*cos(6.0_dp*pi/180.0_dp)
    area = polygon_area(arch%polygon(7)%xy)
    call assert_close(area, expected, 'voussoir area [m2] (trapezoid)', rtol=1.0e-12_dp)
    ! Springing joints are radial: inclined by (180 - 156)/2 = 12 degrees.
    associate (d => arch%joint_extrados_xy(:, 0) - arch%joint_intrados_xy(:, 0))
      call assert_close(atan2(d(2), -d(1))*180.0_dp/pi, 12.0_dp, 'left springing inclination [deg]', &
                        rtol=1.0e-12_dp)
    end associate
    ! Keystone symmetric about x = 0; every voussoir is convex.
    call assert_close(sum(arch%polygon(7)%xy(1, :)), 0.0_dp, 'keystone symmetric', atol=1.0e-14_dp)
    do j = 1, arch%n_bodies
      call assert_true(is_convex_ccw(arch%polygon(j)%xy), 'arch body is convex and counter-clockwise')
    end do
  end subroutine arch_geometry

  subroutine contacts()
    real(dp) :: ground(2, 4), blk(2, 4), points(2, 2), gaps(2), normal(2)
    integer :: n
    logical :: a_cand
    ground = reshape([-1.0_dp, -1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp, 0.0_dp, -1.0_dp, 0.0_dp], [2, 4])
    ! Block 0.4 wide floating 1 mm above the ground.
    blk = reshape([-0.2_dp, 0.001_dp, 0.2_dp, 0.001_dp, 0.2_dp, 0.5_dp, -0.2_dp, 0.5_dp], [2, 4])
    call polygon_contact(blk, ground, 0.01_dp, 0.0_dp, n, points, gaps, normal, a_cand)
    call assert_true(n == 2 .and. a_cand, 'block on ground: two points, block is candidate')
    call assert_close(normal(2), 1.0_dp, 'normal points up from the ground', rtol=1.0e-14_dp)
    call assert_close(gaps(1), 0.001_dp, 'gap [m]', rtol=1.0e-12_dp)
    call assert_close(minval(points(1, :)), -0.2_dp, 'left contact point at the corner [m]', rtol=1.0e-12_dp)
    call polygon_contact(blk, ground, 0.01_dp, 0.03_dp, n, points, gaps, normal, a_cand)
    call assert_close(minval(points(1, :)), -0.17_dp, 'inset moves the point 30 mm inwards [m]', rtol=1.0e-12_dp)
    call assert_close(maxval(points(1, :)), 0.17_dp, 'inset on the other end [m]', rtol=1.0e-12_dp)
    ! Out of the alert distance: nothing.
    blk(2, :) = blk(2, :) + 0.02_dp
    call polygon_contact(blk, ground, 0.01_dp, 0.0_dp, n, points, gaps, normal, a_cand)
    call assert_true(n == 0, 'no contact beyond the alert distance')
    ! Overhanging block: the overlap ends at the ground's edge x = 1.
    blk = reshape([0.8_dp, 0.0_dp, 1.4_dp, 0.0_dp, 1.4_dp, 0.5_dp, 0.8_dp, 0.5_dp], [2, 4])
    call polygon_contact(blk, ground, 0.01_dp, 0.0_dp, n, points, gaps, normal, a_cand)
    call assert_close(maxval(points(1, :)), 1.0_dp, 'overlap clipped at the ground edge [m]', rtol=1.0e-12_dp)
    ! Tilted block resting on one corner: one point at gap 0, the other lifted by 0.4 sin(0.1).
    blk = reshape([-0.2_dp, 0.0_dp, 0.2_dp, 0.0_dp, 0.2_dp, 0.5_dp, -0.2_dp, 0.5_dp], [2, 4])
    blk = tilt(blk, 0.1_dp)
    call polygon_contact(blk, ground, 0.1_dp, 0.0_dp, n, points, gaps, normal, a_cand)
    call assert_close(minval(gaps), 0.0_dp, 'tilted block: pivot corner touches', atol=1.0e-14_dp)
    call assert_close(maxval(gaps), 0.4_dp*sin(0.1_dp), 'tilted block: other corner lifted [m]', rtol=1.0e-12_dp)
  end subroutine contacts

  !> Rotate about the first vertex.
  function tilt(p, angle) result(q)
    real(dp), intent(in) :: p(:, :), angle
    real(dp) :: q(2, size(p, 2)), d(2)
    integer :: k
    do k = 1, size(p, 2)
      d = p(:, k) - p(:, 1)
      q(:, k) = p(:, 1) + [cos(angle)*d(1) - sin(angle)*d(2), sin(angle)*d(1) + cos(angle)*d(2)]
    end do
  end function tilt

  subroutine local_solver()
    real(dp) :: r(2)
    ! Diagonal W = diag(2, 1): approaching at u_n = -1 with no tangential motion sticks
    ! with r = (0, 1).
    call coulomb_local(2.0_dp, 0.0_dp, 1.0_dp, 2.0_dp, 0.0_dp, -1.0_dp, 0.5_dp, r)
    call assert_close(r(2), 1.0_dp, 'stick: normal impulse', rtol=1.0e-14_dp)
    call assert_close(r(1), 0.0_dp, 'stick: no tangential impulse', atol=1.0e-14_dp)
    ! Separating: no impulse.
    call coulomb_local(2.0_dp, 0.0_dp, 1.0_dp, 2.0_dp, 3.0_dp, 0.5_dp, 0.5_dp, r)
    call assert_true(all(r == 0.0_dp), 'separating: no impulse')
    ! Sliding: u_t = 4 needs r_t = -2 to stop, more than mu r_n = 0.5: slide with
    ! r = (-0.5, 1), leaving u_t = 4 - 2 * 0.5 = 3 > 0.
    call coulomb_local(2.0_dp, 0.0_dp, 1.0_dp, 2.0_dp, 4.0_dp, -1.0_dp, 0.5_dp, r)
    call assert_close(r(1), -0.5_dp, 'slide: r_t = -mu r_n', rtol=1.0e-14_dp)
    call assert_close(r(2), 1.0_dp, 'slide: r_n', rtol=1.0e-14_dp)
    ! Coupled W = [[2, 0.5], [0.5, 1]], u_free = (-4, -1), mu = 0.3: slide in -t with
    ! r_t = +0.3 r_n; u_n = -1 + 0.5 (0.3 r_n) + r_n = 0 -> r_n = 1 / 1.15.
    call coulomb_local(2.0_dp, 0.5_dp, 1.0_dp, 1.75_dp, -4.0_dp, -1.0_dp, 0.3_dp, r)
    call assert_close(r(2), 1.0_dp/1.15_dp, 'coupled slide: r_n', rtol=1.0e-13_dp)
    call assert_close(r(1), 0.3_dp/1.15_dp, 'coupled slide: r_t', rtol=1.0e-13_dp)
  end subroutine local_solver

  subroutine afd_waveform()
    type(motion_t) :: m, m2
    real(dp) :: x, v, a, xp, xm, vp, vm, h, t
    integer :: k
    m = motion_afd(2.0_dp, 0.01_dp, 1, 1, 1)
    ! In the full cycles: u = A sin(2 pi f t), peak acceleration A (2 pi f)^2.
    call motion_eval(m, 0.5_dp + 0.125_dp, x, v, a)
    call assert_close(x, 0.01_dp, 'afd full cycle displacement [m]', rtol=1.0e-12_dp)
    call assert_close(-a, 0.01_dp*(4.0_dp*pi)**2, 'afd full cycle peak acceleration [m/s2]', rtol=1.0e-12_dp)
    ! Velocity and acceleration are the derivatives of the displacement, everywhere.
    h = 1.0e-6_dp
    do k = 1, 29
      t = 0.05_dp*k - 0.013_dp
      call motion_eval(m, t, x, v, a)
      call motion_eval(m, t + h, xp, vp, a)
      call motion_eval(m, t - h, xm, vm, a)
      call motion_eval(m, t, x, v, a)
      call assert_close(v, (xp - xm)/(2*h), 'afd velocity = du/dt', atol=1.0e-7_dp)
      call assert_close(a, (vp - vm)/(2*h), 'afd acceleration = dv/dt', atol=1.0e-5_dp)
    end do
    call motion_eval(m, 1.6_dp, x, v, a)
    call assert_true(x == 0.0_dp .and. v == 0.0_dp, 'afd: at rest after the decay')
    ! Actuator model: the table plays the command 10 % larger, 20 ms late.
    m2 = motion_afd(2.0_dp, 0.01_dp, 1, 1, 1, gain=1.1_dp, delay_s=0.02_dp)
    do k = 1, 9
      t = 0.17_dp*k
      call motion_eval(m, t - 0.02_dp, x, v, a)
      call motion_eval(m2, t, xp, vp, h)
      call assert_close(xp, 1.1_dp*x, 'actuator model displacement = gain x command(t - delay)', atol=1.0e-15_dp)
      call assert_close(h, 1.1_dp*a, 'actuator model acceleration = gain x command(t - delay)', atol=1.0e-12_dp)
    end do
  end subroutine afd_waveform

  !> &motion lead_s (motion_t%start_s): the table still until then, the motion shifted by
  !> it (dyadic times, so the shift is exact) and its end later by it.
  subroutine motion_lead()
    type(motion_t) :: m, led
    real(dp) :: x, v, a, xl, vl, al
    integer :: k
    m = motion_afd(2.0_dp, 0.01_dp, 1, 1, 1)
    led = m
    led%start_s = 0.25_dp
    call assert_close(motion_duration_s(led), motion_duration_s(m) + 0.25_dp, 'afd lead: the end later by it', &
                      rtol=1.0e-15_dp)
    do k = 1, 7
      call motion_eval(led, 0.03125_dp*k, xl, vl, al)
      call assert_true(xl == 0.0_dp .and. vl == 0.0_dp .and. al == 0.0_dp, 'afd lead: the table still before it')
    end do
    do k = 0, 12
      call motion_eval(m, 0.125_dp*k, x, v, a)
      call motion_eval(led, 0.25_dp + 0.125_dp*k, xl, vl, al)
      call assert_true(xl == x .and. vl == v .and. al == a, 'afd lead: the motion played lead_s later')
    end do
    m = motion_ramp(0.5_dp)
    m%start_s = 0.25_dp
    call motion_eval(m, 0.125_dp, x, v, a)
    call assert_true(a == 0.0_dp, 'ramp lead: no load before it')
    call motion_eval(m, 0.75_dp, x, v, a)
    call assert_close(a, 0.25_dp, 'ramp lead: the load grows from lead_s', rtol=1.0e-15_dp)
    call assert_close(motion_duration_s(m), 0.25_dp, 'ramp lead: its end is its start', rtol=1.0e-15_dp)
  end subroutine motion_lead

end program test_geometry_contacts
