!> The coarse correction of the contact solve (voussoir_coarse) against a closed form: a
!> stack of N equal blocks at rest on the ground, one block per course. Over one step
!> of the theta method the end velocity is zero, so the normal impulses of the bed
!> joint under course k add up to the weight of courses k to N times the time step,
!> (N - k + 1) m g h, and by symmetry its two contact points carry half each. The
!> exact impulses lie in the coarse space, so one coarse solve from zero impulses gives
!> them; a whole step with the correction then converges in a few sweeps, where
!> Gauss-Seidel alone carries the weight down one course per sweep.
program test_coarse
  use voussoir_kinds, only: dp, g_m_s2
  use voussoir_status, only: status_t
  use voussoir_assembly, only: assembly_t
  use voussoir_wall_config, only: wall_config_t
  use voussoir_wall, only: build_wall
  use voussoir_model, only: model_t, model_step, solver_settings_t
  use voussoir_motion, only: motion_afd
  use voussoir_contact_law, only: contact_law_t, pair_friction_t
  use voussoir_setup, only: init_model
  use voussoir_bodies, only: update_world_vertices
  use voussoir_contacts, only: detect_contacts
  use voussoir_nlgs, only: nlgs_prepare
  use voussoir_coarse, only: coarse_init, coarse_correct
  use voussoir_assert, only: assert_true, assert_close, assert_summary
  implicit none

  integer, parameter :: n_courses = 20
  real(dp), parameter :: h_s = 1.0e-3_dp
  integer :: sweeps_tight, sweeps_coarse, sweeps_plain

  call one_coarse_solve()
  call whole_step(.true., 1.0e-8_dp, sweeps_tight)
  call assert_true(sweeps_tight <= 10, 'stack of 20, tol 1e-8: a settling step converges in at most 10 sweeps')
  call whole_step(.true., 1.0e-4_dp, sweeps_coarse)
  call whole_step(.false., 1.0e-4_dp, sweeps_plain)
  write (*, '(a,i0,a,i0,a)') '      one settling step of the stack, tol 1e-4: ', sweeps_coarse, &
    ' sweeps with the correction, ', sweeps_plain, ' without'
  call assert_true(sweeps_plain > n_courses .and. sweeps_coarse < sweeps_plain/4, &
                   'stack of 20, tol 1e-4: Gauss-Seidel alone needs more sweeps than courses, 4 times those with the correction')
  call assert_summary()

contains

  !> The model of the stack at rest, with or without the coarse correction.
  subroutine stack_model(with_coarse, tol, model)
    logical, intent(in) :: with_coarse
    real(dp), intent(in) :: tol
    type(model_t), intent(out) :: model
    type(assembly_t) :: stack
    type(solver_settings_t) :: s
    type(status_t) :: status
    type(pair_friction_t) :: no_pairs(0)
    call build_wall(wall_config_t(courses=n_courses, blocks_per_course=1, bond='stack'), stack)
    s%dt_s = h_s
    s%tol = tol
    s%max_iter = 100000
    call init_model(stack, 2000.0_dp, 0.1_dp, s, contact_law_t(friction=0.6_dp, pairs=no_pairs), model, status)
    call assert_true(status%ok, 'stack model: '//trim(status%message))
    model%motion = motion_afd(1.0_dp, 0.0_dp, 1, 1, 1)
    if (with_coarse) call coarse_init(model%coarse, stack%course, model%bodies%inv_mass, model%bodies%inv_inertia)
  end subroutine stack_model

  !> The closed form, joint by joint: the sum of the normal impulses between course k - 1
  !> and course k, and each of its points at half of it.
  subroutine check_impulses(model, rtol, what)
    type(model_t), intent(in) :: model
    real(dp), intent(in) :: rtol
    character(len=*), intent(in) :: what
    real(dp) :: total(n_courses), expected, worst_point
    integer :: k, j, points(n_courses)
    total = 0.0_dp
    points = 0
    worst_point = 0.0_dp
    associate (c => model%contacts)
      do k = 1, c%n
        j = max(c%body_a(k), c%body_b(k)) - 1   ! body 1 is the ground, body k + 1 course k
        total(j) = total(j) + c%impulse(2, k)
        points(j) = points(j) + 1
      end do
      call assert_true(all(points == 2), what//': two contact points per bed joint')
      do k = 1, c%n
        j = max(c%body_a(k), c%body_b(k)) - 1
        expected = 0.5_dp*(n_courses - j + 1)*model%bodies%mass_kg(2)*g_m_s2*h_s
        worst_point = max(worst_point, abs(c%impulse(2, k) - expected)/expected)
      end do
    end associate
    do j = 1, n_courses, n_courses/4
      expected = (n_courses - j + 1)*model%bodies%mass_kg(2)*g_m_s2*h_s
      call assert_close(total(j), expected, what//': normal impulse under course '//achar(iachar('0') + j/10)// &
                        achar(iachar('0') + mod(j, 10))//' = weight above x dt', rtol=rtol)
    end do
    call assert_true(joint_error(model) <= rtol, what//': every bed joint within the tolerance')
    call assert_true(worst_point <= rtol, what//': every contact point at half its joint')
  end subroutine check_impulses

  !> From zero impulses, one coarse solve and no sweep: the impulses are the exact ones
  !> and every block's end velocity is zero.
  subroutine one_coarse_solve()
    type(model_t) :: model
    integer :: i
    call stack_model(.true., 1.0e-4_dp, model)
    associate (b => model%bodies, c => model%contacts)
      call update_world_vertices(b, b%q)
      call detect_contacts(b, b%q, model%solver%alert_m, model%law, c)
      call nlgs_prepare(b, c, model%solver%theta*h_s, model%work)
      c%impulse(:, 1:c%n) = 0.0_dp
      do i = 1, b%n
        if (.not. b%driven(i)) b%v(:, i) = [0.0_dp, -g_m_s2*h_s, 0.0_dp]
      end do
      call coarse_correct(model%coarse, c%n, b%n, model%work%pair, model%work%data, c%point, c%impulse, b%v)
      call check_impulses(model, 1.0e-10_dp, 'one coarse solve')
      call assert_true(maxval(abs(b%v)) <= 1.0e-10_dp*g_m_s2*h_s, 'one coarse solve: every block at rest at the end')
    end associate
  end subroutine one_coarse_solve

  !> One Moreau-Jean step from rest to the tolerance `tol`: the sweeps it takes. With the
  !> correction, the impulses to 1e-6 at tol 1e-8 and to 1e-2 at 1e-4; without it, only
  !> the error is printed (Gauss-Seidel stops on a small change per sweep, not a small
  !> error: a few per cent at tol 1e-4).
  subroutine whole_step(with_coarse, tol, sweeps)
    logical, intent(in) :: with_coarse
    real(dp), intent(in) :: tol
    integer, intent(out) :: sweeps
    type(model_t) :: model
    type(status_t) :: status
    character(len=40) :: what
    call stack_model(with_coarse, tol, model)
    call model_step(model, status)
    write (what, '(a,es7.0)') merge('step with the correction,    tol', 'step without the correction, tol', with_coarse), tol
    call assert_true(status%ok .and. model%converged, trim(what)//': converged '//trim(status%message))
    sweeps = model%iterations
    if (with_coarse) then
      call check_impulses(model, merge(1.0e-6_dp, 1.0e-2_dp, tol < 1.0e-6_dp), trim(what))
    else
      write (*, '(a,es9.2)') '      '//trim(what)//': largest relative error of a bed joint''s impulse ', &
        joint_error(model)
    end if
  end subroutine whole_step

  !> The largest relative error of the bed joints' normal impulses.
  real(dp) function joint_error(model)
    type(model_t), intent(in) :: model
    real(dp) :: total(n_courses), expected
    integer :: k, j
    total = 0.0_dp
    do k = 1, model%contacts%n
      j = max(model%contacts%body_a(k), model%contacts%body_b(k)) - 1
      total(j) = total(j) + model%contacts%impulse(2, k)
    end do
    joint_error = 0.0_dp
    do j = 1, n_courses
      expected = (n_courses - j + 1)*model%bodies%mass_kg(2)*g_m_s2*h_s
      joint_error = max(joint_error, abs(total(j) - expected)/expected)
    end do
  end function joint_error

end program test_coarse
