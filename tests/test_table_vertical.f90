!> A rigid block on a table that accelerates sideways (a_h) and vertically (a_v, upwards)
!> at constant rates, against the closed form (shared/DESIGN.md's statics in the frame of
!> the table, where the block carries its weight m (g + a_v) and the inertial load m a_h):
!> - a wide block (friction only) slides when a_h > mu (g + a_v), and then slides on the
!>   table with the relative acceleration a_h - mu (g + a_v);
!> - a slender block of half-width b and half-height h with high friction tips when
!>   a_h > (b/h) (g + a_v).
!> Each onset is checked at 0.97 and 1.03 of its closed form for an upward, a downward
!> and no vertical acceleration, and a downward a_v is shown to lower both: at 0.9 of the
!> onset without it, the block stays without a_v and moves with a_v = -0.3 g.
!> The accelerations are accelerograms: a linear ramp of 0.1 s to the constant value,
!> kept for 1.2 s.
program test_table_vertical
  use voussoir_kinds, only: dp, g_m_s2
  use voussoir_status, only: status_t
  use voussoir_assembly, only: assembly_t, polygon_t, role_voussoir, role_foundation
  use voussoir_model, only: model_t, model_step, solver_settings_t
  use voussoir_motion, only: motion_accelerogram, motion_set_vertical_record
  use voussoir_setup, only: init_model
  use voussoir_contact_law, only: contact_law_t, contact_law_init
  use voussoir_assert, only: assert_true, assert_close, assert_summary
  implicit none

  real(dp), parameter :: record_dt_s = 0.01_dp, ramp_s = 0.1_dp, hold_s = 1.2_dp
  !> The wide block (sliding) and the slender one (tipping): half sizes [m], friction.
  real(dp), parameter :: wide_b = 0.5_dp, wide_h = 0.05_dp, wide_mu = 0.3_dp
  real(dp), parameter :: slender_b = 0.1_dp, slender_h = 0.4_dp, slender_mu = 0.9_dp
  real(dp) :: av(3)
  integer :: k

  av = [0.3_dp*g_m_s2, 0.0_dp, -0.3_dp*g_m_s2]
  do k = 1, size(av)
    call check_sliding(av(k), 0.97_dp, moves=.false.)
    call check_sliding(av(k), 1.03_dp, moves=.true.)
    call check_tipping(av(k), 0.97_dp, moves=.false.)
    call check_tipping(av(k), 1.03_dp, moves=.true.)
  end do
  ! A downward a_v lowers both onsets: 0.9 of the onsets without it.
  call check_moves(wide_b, wide_h, wide_mu, 0.9_dp*wide_mu*g_m_s2, 0.0_dp, .false., 'slide', &
                   'a_h = 0.9 mu g, no a_v: the wide block stays')
  call check_moves(wide_b, wide_h, wide_mu, 0.9_dp*wide_mu*g_m_s2, -0.3_dp*g_m_s2, .true., 'slide', &
                   'a_h = 0.9 mu g, a_v = -0.3 g: the wide block slides')
  call check_moves(slender_b, slender_h, slender_mu, 0.9_dp*slender_b/slender_h*g_m_s2, 0.0_dp, .false., 'tip', &
                   'a_h = 0.9 (b/h) g, no a_v: the slender block stands')
  call check_moves(slender_b, slender_h, slender_mu, 0.9_dp*slender_b/slender_h*g_m_s2, -0.3_dp*g_m_s2, .true., &
                   'tip', 'a_h = 0.9 (b/h) g, a_v = -0.3 g: the slender block tips')
  call assert_summary()

contains

  subroutine check_sliding(a_v, fraction, moves)
    real(dp), intent(in) :: a_v, fraction
    logical, intent(in) :: moves
    character(len=96) :: label
    write (label, '(a,f0.2,a,f0.2,a)') 'wide block, a_v = ', a_v/g_m_s2, ' g, a_h = ', fraction, ' mu (g + a_v)'
    call check_moves(wide_b, wide_h, wide_mu, fraction*wide_mu*(g_m_s2 + a_v), a_v, moves, 'slide', label)
  end subroutine check_sliding

  subroutine check_tipping(a_v, fraction, moves)
    real(dp), intent(in) :: a_v, fraction
    logical, intent(in) :: moves
    character(len=96) :: label
    write (label, '(a,f0.2,a,f0.2,a)') 'slender block, a_v = ', a_v/g_m_s2, ' g, a_h = ', fraction, ' (b/h) (g + a_v)'
    call check_moves(slender_b, slender_h, slender_mu, fraction*slender_b/slender_h*(g_m_s2 + a_v), a_v, moves, &
                     'tip', label)
  end subroutine check_tipping

  !> Run the block (half sizes b, h; friction mu) on the table under the constant a_h,
  !> a_v and check whether it moves as `mechanism` ('slide' or 'tip') or stays.
  subroutine check_moves(b, h, mu, a_h, a_v, moves, mechanism, label)
    real(dp), intent(in) :: b, h, mu, a_h, a_v
    logical, intent(in) :: moves
    character(len=*), intent(in) :: mechanism, label
    type(model_t) :: model
    type(status_t) :: status
    type(polygon_t) :: ground
    real(dp), allocatable :: ramp(:)
    real(dp) :: slip_m, slip_v1, t1, rotation, rise_m
    integer :: n_ramp, n_hold, k, n_steps

    n_ramp = nint(ramp_s/record_dt_s)
    n_hold = nint(hold_s/record_dt_s)
    ramp = [(real(min(k, n_ramp), dp)/n_ramp, k = 0, n_ramp + n_hold)]
    ground%xy = reshape([-2.0_dp, -0.5_dp, 2.0_dp, -0.5_dp, 2.0_dp, 0.0_dp, -2.0_dp, 0.0_dp], [2, 4])
    call init_model(two_bodies(block(b, h), ground), 2000.0_dp, 1.0_dp, settings(), law(mu), model, status)
    call assert_true(status%ok, trim(label)//': model builds')
    model%motion = motion_accelerogram(a_h*ramp, record_dt_s, 0.0_dp)
    call motion_set_vertical_record(model%motion, a_v*ramp)
    n_steps = nint((ramp_s + hold_s)/model%solver%dt_s)
    slip_v1 = 0.0_dp
    t1 = 0.0_dp
    do k = 1, n_steps
      call model_step(model, status)
      if (.not. status%ok) exit
      ! The sliding velocity on the table, from the middle of the held acceleration on.
      if (k == nint((ramp_s + 0.5_dp*hold_s)/model%solver%dt_s)) then
        slip_v1 = model%bodies%v(1, 1) - model%table(2)
        t1 = model%t_s
      end if
      if (mechanism == 'tip' .and. abs(model%bodies%q(3, 1)) > 1.0e-3_dp) exit
    end do
    call assert_true(status%ok, trim(label)//': run '//trim(status%message))
    slip_m = model%bodies%q(1, 1) - model%bodies%q_ref(1, 1) - model%table(1)
    rotation = model%bodies%q(3, 1)
    ! The table has carried the block up (or let it down) with it: it stays on the table.
    rise_m = model%bodies%q(2, 1) - model%bodies%q_ref(2, 1) - model%table_vertical(1)
    call assert_close(model%table_vertical(1), a_v*(0.5_dp*ramp_s*ramp_s/3.0_dp + 0.5_dp*ramp_s*(model%t_s - ramp_s) + &
                      0.5_dp*(model%t_s - ramp_s)**2), trim(label)//': table rise [m] (exact integral)', &
                      rtol=1.0e-9_dp, atol=1.0e-12_dp)
    if (mechanism == 'slide') then
      if (moves) then
        call assert_true(abs(slip_m) > 1.0e-2_dp, trim(label)//': slides')
        ! Sliding against the table's acceleration with a_h - mu (g + a_v) relative to it.
        call assert_close((model%bodies%v(1, 1) - model%table(2) - slip_v1)/(model%t_s - t1), &
                          -(a_h - mu*(g_m_s2 + a_v)), trim(label)//': sliding acceleration on the table [m/s2]', &
                          rtol=0.02_dp)
      else
        call assert_true(abs(slip_m) < 1.0e-5_dp, trim(label)//': sticks')
      end if
      call assert_true(abs(rotation) < 1.0e-6_dp .and. abs(rise_m) < 1.0e-5_dp, &
                       trim(label)//': stays flat on the table')
    else
      if (moves) then
        call assert_true(abs(rotation) > 1.0e-3_dp, trim(label)//': tips')
      else
        call assert_true(abs(rotation) < 1.0e-6_dp .and. abs(rise_m) < 1.0e-5_dp, trim(label)//': stands')
      end if
      call assert_true(pivot_slip_m(model, b) < 1.0e-5_dp, trim(label)//': does not slide (its pivot corner)')
    end if
  end subroutine check_moves

  !> The smaller horizontal slip on the table [m] of the block's two bottom corners, (-b, 0)
  !> and (b, 0) at rest: a tipping block turns about one of them.
  real(dp) function pivot_slip_m(model, b)
    type(model_t), intent(in) :: model
    real(dp), intent(in) :: b
    real(dp) :: c, s, arm(2), moved_x
    integer :: side
    c = cos(model%bodies%q(3, 1))
    s = sin(model%bodies%q(3, 1))
    pivot_slip_m = huge(1.0_dp)
    do side = -1, 1, 2
      arm = [side*b, 0.0_dp] - model%bodies%q_ref(1:2, 1)
      moved_x = model%bodies%q(1, 1) + c*arm(1) - s*arm(2)
      pivot_slip_m = min(pivot_slip_m, abs(moved_x - side*b - model%table(1)))
    end do
  end function pivot_slip_m

  !> A rectangle of half sizes b, h standing on y = 0, centred on x = 0.
  function block(b, h) result(p)
    real(dp), intent(in) :: b, h
    type(polygon_t) :: p
    p%xy = reshape([-b, 0.0_dp, b, 0.0_dp, b, 2*h, -b, 2*h], [2, 4])
  end function block

  !> One free block on one driven ground polygon, numbered as a one-voussoir arch.
  function two_bodies(free_block, ground) result(a)
    type(polygon_t), intent(in) :: free_block, ground
    type(assembly_t) :: a
    a%n_bodies = 2
    a%polygon = [free_block, ground]
    a%driven = [.false., .true.]
    a%role = [role_voussoir, role_foundation]
    a%n_voussoirs = 1
    allocate (a%joint_bodies(2, 0:1))
    a%joint_bodies(:, 0) = [2, 1]
    a%joint_bodies(:, 1) = [1, 2]
  end function two_bodies

  function settings() result(s)
    type(solver_settings_t) :: s
    s%dt_s = 1.0e-3_dp
    s%tol = 1.0e-8_dp
    s%max_iter = 5000
    s%alert_m = 1.0e-3_dp
  end function settings

  !> Friction `mu` on every contact.
  function law(mu) result(l)
    real(dp), intent(in) :: mu
    type(contact_law_t) :: l
    type(status_t) :: status
    type(polygon_t) :: none
    real(dp) :: joint_friction(0:1)
    allocate (none%xy(2, 0))
    joint_friction = -1.0_dp   ! none set: mu on every joint
    call contact_law_init(mu, 0.0_dp, joint_friction, two_bodies(none, none), l, status)
    call assert_true(status%ok, 'contact law: '//trim(status%message))
  end function law

end program test_table_vertical
