!> Latin hypercube samples (src/latin_hypercube.f90) and the seeded size imperfection of
!> an arch (src/assembly.f90's voussoir_angle_factors, build_arch).
program test_latin_hypercube
  use voussoir_kinds, only: dp, pi
  use voussoir_latin_hypercube, only: latin_hypercube
  use voussoir_assembly, only: assembly_t, build_arch, voussoir_angle_factors, arch_joint_angle_deg
  use voussoir_assert, only: assert_true, assert_close, assert_summary
  implicit none

  real(dp) :: u(4, 20), w(4, 20), f(13), ang
  integer :: v, k, j
  logical :: one_each
  type(assembly_t) :: arch

  ! One sample per stratum in every variable.
  u = latin_hypercube(20, 4, 7)
  call assert_true(all(u > 0.0_dp .and. u < 1.0_dp), 'samples inside the unit cube')
  one_each = .true.
  do v = 1, 4
    do k = 0, 19
      one_each = one_each .and. count(floor(20.0_dp*u(v, :)) == k) == 1
    end do
  end do
  call assert_true(one_each, 'every variable has exactly one sample in each of the 20 strata')
  ! The strata are shuffled independently: the variables are not in the same order.
  call assert_true(any(floor(20.0_dp*u(1, :)) /= floor(20.0_dp*u(2, :))), 'variables shuffled independently')
  w = latin_hypercube(20, 4, 7)
  call assert_true(all(w == u), 'the same seed gives the same samples')
  w = latin_hypercube(20, 4, 8)
  call assert_true(any(w /= u), 'another seed gives other samples')
  u(:, 1:1) = latin_hypercube(1, 4, 3)
  call assert_true(all(u(:, 1) > 0.0_dp .and. u(:, 1) < 1.0_dp), 'one sample: anywhere in the cube')

  ! Size imperfection: angles of mean 1 within 1 +- 2 amplitude, none without amplitude.
  f = voussoir_angle_factors(13, 0.1_dp, 5)
  call assert_close(sum(f)/13.0_dp, 1.0_dp, 'angle factors have mean 1', rtol=1.0e-14_dp)
  call assert_true(all(abs(f - 1.0_dp) < 0.2_dp) .and. any(abs(f - 1.0_dp) > 0.02_dp), &
                   'angle factors within 1 +- 2 x 0.1, and not all equal')
  call assert_true(all(voussoir_angle_factors(13, 0.0_dp, 5) == 1.0_dp), 'no imperfection: equal voussoirs')
  call assert_true(any(voussoir_angle_factors(13, 0.1_dp, 6) /= f), 'another seed, another pattern')
  ! The imperfect arch: springings where they were, voussoir j spans f(j) embrace/n.
  call build_arch(156.0_dp, 13, 0.508_dp, 0.071_dp, arch, angle_factors=f)
  call assert_close(arch%joint_extrados_xy(1, 0), 0.508_dp*cos(arch_joint_angle_deg(156.0_dp, 13, 0)*pi/180.0_dp), &
                    'left springing unchanged', atol=1.0e-14_dp)
  call assert_close(arch%joint_extrados_xy(1, 13), 0.508_dp*cos(arch_joint_angle_deg(156.0_dp, 13, 13)*pi/180.0_dp), &
                    'right springing unchanged', atol=1.0e-12_dp)
  do j = 1, 13
    ang = atan2(arch%joint_extrados_xy(2, j - 1), arch%joint_extrados_xy(1, j - 1)) - &
          atan2(arch%joint_extrados_xy(2, j), arch%joint_extrados_xy(1, j))
    call assert_close(ang*180.0_dp/pi, f(j)*156.0_dp/13.0_dp, 'voussoir angle = factor x embrace/n', rtol=1.0e-10_dp)
  end do

  call assert_summary()
end program test_latin_hypercube
