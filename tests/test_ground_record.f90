!> Ground-motion records (src/ground_record.f90) and the accelerogram table motion
!> (src/motion.f90) against hand computations.
program test_ground_record
  use voussoir_kinds, only: dp, pi, g_m_s2
  use voussoir_ground_record, only: record_intensity_t, record_intensity, integrate_linear_accel
  use voussoir_motion, only: motion_t, motion_accelerogram, motion_eval, motion_duration_s
  use voussoir_assert, only: assert_true, assert_close, assert_summary
  implicit none

  type(record_intensity_t) :: im
  type(motion_t) :: m
  real(dp) :: v(3), x(3), xt, vt, at

  ! A constant acceleration c over T = 4 dt: v = c t, x = c t^2/2; Arias pi/(2g) c^2 T;
  ! the integral of a^2 grows linearly, so t5 = 0.05 T and t95 = 0.95 T.
  im = record_intensity([2.0_dp, 2.0_dp, 2.0_dp, 2.0_dp, 2.0_dp], 0.5_dp)
  call assert_close(im%pga_m_s2, 2.0_dp, 'constant: PGA', rtol=1.0e-12_dp)
  call assert_close(im%pgv_m_s, 4.0_dp, 'constant: PGV = c T', rtol=1.0e-12_dp)
  call assert_close(im%arias_m_s, pi/(2.0_dp*g_m_s2)*4.0_dp*2.0_dp, 'constant: Arias', rtol=1.0e-12_dp)
  call assert_close(im%t5_s, 0.1_dp, 'constant: t5 = 0.05 T', atol=1.0e-12_dp)
  call assert_close(im%t95_s, 1.9_dp, 'constant: t95 = 0.95 T', rtol=1.0e-12_dp)
  call assert_close(im%significant_duration_s, 1.8_dp, 'constant: D5-95 = 0.9 T', rtol=1.0e-12_dp)

  ! a = 1 then -1 over one step dt = 2: v(t) = t - t^2/dt peaks inside the step at
  ! t = dt/2 with v = dt/4 = 0.5, and is back to 0 at the second sample.
  im = record_intensity([1.0_dp, -1.0_dp], 2.0_dp)
  call assert_close(im%pgv_m_s, 0.5_dp, 'sign change: PGV inside the step', rtol=1.0e-12_dp)
  ! The integral of (1 - t)^2 over [0, 2] is 2/3.
  call assert_close(im%arias_m_s, pi/(2.0_dp*g_m_s2)*2.0_dp/3.0_dp, 'sign change: Arias', rtol=1.0e-12_dp)
  ! Half of the integral of (1 - t)^2 is reached at t = 1 (symmetry): 5 % where
  ! (1 - (1 - t)^3)/3 = 0.05 * 2/3, i.e. t = 1 - 0.9^(1/3).
  call assert_close(im%t5_s, 1.0_dp - 0.9_dp**(1.0_dp/3.0_dp), 'sign change: t5', atol=1.0e-12_dp)

  ! Exact integrals at the samples of a = [0, 3, 3] with dt = 1: v = [0, 1.5, 4.5],
  ! x(1) = integral of 1.5 t^2 = 0.5, x(2) = 0.5 + 1.5 + 1.5 = 3.5.
  call integrate_linear_accel([0.0_dp, 3.0_dp, 3.0_dp], 1.0_dp, v, x)
  call assert_close(v(2), 1.5_dp, 'integrals: v at sample 2', rtol=1.0e-12_dp)
  call assert_close(v(3), 4.5_dp, 'integrals: v at sample 3', rtol=1.0e-12_dp)
  call assert_close(x(2), 0.5_dp, 'integrals: x at sample 2', rtol=1.0e-12_dp)
  call assert_close(x(3), 3.5_dp, 'integrals: x at sample 3', rtol=1.0e-12_dp)

  ! The table: at rest until start_s, then the record, then constant velocity.
  m = motion_accelerogram([0.0_dp, 3.0_dp, 3.0_dp], 1.0_dp, 0.25_dp)
  call assert_close(motion_duration_s(m), 2.25_dp, 'table: duration = lead + record', rtol=1.0e-12_dp)
  call motion_eval(m, 0.2_dp, xt, vt, at)
  call assert_true(xt == 0.0_dp .and. vt == 0.0_dp .and. at == 0.0_dp, 'table: at rest before start_s')
  call motion_eval(m, 0.75_dp, xt, vt, at)  ! half way through the first step: a = 3 t
  call assert_close(at, 1.5_dp, 'table: a linear between samples', rtol=1.0e-12_dp)
  call assert_close(vt, 1.5_dp*0.25_dp, 'table: v = 1.5 t^2', rtol=1.0e-12_dp)
  call assert_close(xt, 0.5_dp*0.125_dp, 'table: x = 0.5 t^3', rtol=1.0e-12_dp)
  call motion_eval(m, 3.25_dp, xt, vt, at)  ! one second after the last sample
  call assert_close(at, 0.0_dp, 'table: no acceleration after the record', atol=0.0_dp)
  call assert_close(vt, 4.5_dp, 'table: final velocity kept', rtol=1.0e-12_dp)
  call assert_close(xt, 3.5_dp + 4.5_dp, 'table: x grows at the final velocity', rtol=1.0e-12_dp)

  call assert_summary()
end program test_ground_record
