!> The contact forces a run records (run_result_t, written to /contacts) against statics
!> derived by hand:
!> - a block of mass m resting on fixed ground: the normal forces of its contacts sum to
!>   m g, and no tangential force, once at rest;
!> - the same block pushed by a slowly growing horizontal inertial load m a(t): while it
!>   sticks the friction force is m a (against the load); above a = mu g (and far below
!>   tipping, g b / h) it slides and the friction force is mu N, N = m g.
program test_contact_forces
  use voussoir_kinds, only: dp, g_m_s2
  use voussoir_status, only: status_t
  use voussoir_assembly, only: assembly_t, polygon_t, role_voussoir, role_foundation
  use voussoir_model, only: model_t, solver_settings_t
  use voussoir_motion, only: motion_afd, motion_ramp
  use voussoir_setup, only: init_model
  use voussoir_contact_law, only: contact_law_t, pair_friction_t
  use voussoir_monitors, only: monitor_t, monitor_init
  use voussoir_simulation, only: run_result_t, simulate
  use voussoir_assert, only: assert_true, assert_close, assert_summary
  implicit none

  real(dp), parameter :: density = 2000.0_dp, width = 0.1_dp, dt = 1.0e-3_dp
  ! A block 0.6 m wide and 0.1 m high: 2000 * 0.1 * 0.06 = 12 kg; it tips at 6 g.
  real(dp), parameter :: half_w = 0.3_dp, half_h = 0.05_dp, mass_kg = density*width*(2*half_w)*(2*half_h)

  call resting_block()
  call pushed_block(mu=0.3_dp, rate_m_s3=10.0_dp)
  call assert_summary()

contains

  !> One free rectangle (half sizes half_w, half_h) on its base at y = 0 and a driven
  !> ground slab below it; not an arch (no joints).
  function block_on_ground() result(a)
    type(assembly_t) :: a
    type(polygon_t) :: block, ground
    block%xy = reshape([-half_w, 0.0_dp, half_w, 0.0_dp, half_w, 2*half_h, -half_w, 2*half_h], [2, 4])
    ground%xy = reshape([-2.0_dp, -0.5_dp, 2.0_dp, -0.5_dp, 2.0_dp, 0.0_dp, -2.0_dp, 0.0_dp], [2, 4])
    a%n_bodies = 2
    a%polygon = [block, ground]
    a%driven = [.false., .true.]
    a%role = [role_voussoir, role_foundation]
    a%n_voussoirs = 0
  end function block_on_ground

  !> Run the block for `duration_s` with friction `mu` under `model%motion` as set by `motion_kind`
  !> (1: at rest, 2: a ramp of `rate_m_s3`), sampling every 10 steps.
  subroutine run(mu, motion_kind, rate_m_s3, duration_s, res)
    real(dp), intent(in) :: mu, rate_m_s3, duration_s
    integer, intent(in) :: motion_kind
    type(run_result_t), intent(out) :: res
    type(assembly_t) :: a
    type(model_t) :: model
    type(monitor_t) :: mon
    type(status_t) :: status
    type(solver_settings_t) :: s
    type(pair_friction_t) :: no_pairs(0)
    a = block_on_ground()
    s%dt_s = dt
    s%tol = 1.0e-10_dp
    s%max_iter = 10000
    s%alert_m = 1.0e-3_dp
    call init_model(a, density, width, s, contact_law_t(friction=mu, pairs=no_pairs), model, status)
    call assert_true(status%ok, 'model builds: '//trim(status%message))
    if (motion_kind == 1) then
      model%motion = motion_afd(1.0_dp, 0.0_dp, 1, 1, 1)
    else
      model%motion = motion_ramp(rate_m_s3)
    end if
    call monitor_init(a, model%bodies, 0.05_dp, 0.5_dp, 1.0e-3_dp, mon)
    call simulate(model, mon, duration_s, 10, -1.0_dp, res, status, record_contacts=.true.)
    call assert_true(status%ok, 'run: '//trim(status%message))
  end subroutine run

  !> The total force [N] on the free block (body 1) from its contacts at sample `s`:
  !> the mean force over the step, impulse / dt.
  function force_on_block(res, s) result(f)
    type(run_result_t), intent(in) :: res
    integer, intent(in) :: s
    real(dp) :: f(2), n(2), t(2), on_a(2)
    integer :: k
    f = 0.0_dp
    do k = res%contact_start(s), res%contact_start(s + 1) - 1
      n = res%contact_normal(:, k)
      t = [-n(2), n(1)]
      on_a = (res%contact_impulse(2, k)*n + res%contact_impulse(1, k)*t)/dt
      if (res%contact_bodies(1, k) == 1) then
        f = f + on_a
      else
        f = f - on_a
      end if
    end do
  end function force_on_block

  subroutine resting_block()
    type(run_result_t) :: res
    real(dp) :: f(2)
    integer :: s, k
    call run(0.6_dp, 1, 0.0_dp, 0.5_dp, res)
    s = res%n_samples
    call assert_true(size(res%contact_start) == res%n_samples + 1, 'resting block: an offset per sample and one more')
    call assert_true(res%contact_count(1) == 0, 'resting block: no contact recorded at t = 0 (no step made)')
    call assert_true(res%contact_count(s) == 2, 'resting block: two loaded contact points at the end')
    do k = res%contact_start(s), res%contact_start(s + 1) - 1
      call assert_true(res%contact_joint(k) == -1, 'resting block: no joint index outside an arch')
      call assert_true(all([res%contact_bodies(:, k)] == [1, 2]) .or. all([res%contact_bodies(:, k)] == [2, 1]), &
                       'resting block: contacts join body 1 and the ground (2)')
      call assert_close(abs(res%contact_normal(2, k)), 1.0_dp, 'resting block: normal is vertical', atol=1.0e-12_dp)
      call assert_close(res%contact_point(2, k), 0.0_dp, 'resting block: contact point on the base', atol=1.0e-4_dp)
    end do
    f = force_on_block(res, s)
    call assert_close(f(2), mass_kg*g_m_s2, 'resting block: sum of normal forces = m g [N]', rtol=1.0e-6_dp)
    call assert_close(f(1), 0.0_dp, 'resting block: no tangential force [N]', atol=1.0e-6_dp*mass_kg*g_m_s2)
  end subroutine resting_block

  !> Ramp of load acceleration a(t) = rate t (the step's load at its theta point t - dt/2).
  subroutine pushed_block(mu, rate_m_s3)
    real(dp), intent(in) :: mu, rate_m_s3
    type(run_result_t) :: res
    real(dp) :: f(2), t_slip_s, load
    integer :: s_stick, s_slide
    t_slip_s = mu*g_m_s2/rate_m_s3
    call run(mu, 2, rate_m_s3, 1.5_dp*t_slip_s, res)
    ! A sample at 60 % of the slip load (it sticks) and the last one (at 1.5 times: it slides).
    s_stick = minloc(abs(res%time_s - 0.6_dp*t_slip_s), dim=1)
    s_slide = res%n_samples
    load = mass_kg*rate_m_s3*(res%time_s(s_stick) - 0.5_dp*dt)
    f = force_on_block(res, s_stick)
    call assert_close(f(1), -load, 'pushed block, sticking: friction = -m a [N]', rtol=1.0e-6_dp)
    call assert_close(f(2), mass_kg*g_m_s2, 'pushed block, sticking: N = m g [N]', rtol=1.0e-6_dp)
    f = force_on_block(res, s_slide)
    call assert_close(f(2), mass_kg*g_m_s2, 'pushed block, sliding: N = m g [N]', rtol=1.0e-6_dp)
    call assert_close(f(1), -mu*mass_kg*g_m_s2, 'pushed block, sliding: friction = -mu N [N]', rtol=1.0e-6_dp)
    call assert_true(res%q(1, 1, s_slide) > 1.0e-3_dp, 'pushed block slides along +x')
    call assert_true(abs(res%q(3, 1, s_slide)) < 1.0e-6_dp, 'pushed block does not tip')
  end subroutine pushed_block

end program test_contact_forces
