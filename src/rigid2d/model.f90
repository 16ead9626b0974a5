!> The dynamic model and one Moreau-Jean time step.
!>
!> Step from t to t + h with the theta-method: free velocities under gravity, the
!> inertial load and the constant external loads (&load), predicted configuration
!> q + (1 - theta) h v, contact detection there, NLGS for the end-of-step velocities, then q_end = q_pred + theta h v_end. Driven
!> bodies (foundations, brackets) move with the table velocity, horizontal and (where the
!> motion has one) vertical.
module voussoir_model
  use voussoir_kinds, only: dp, g_m_s2
  use voussoir_status, only: status_t, fail
  use voussoir_bodies, only: bodies_t, update_world_vertices, external_load
  use voussoir_contacts, only: contact_set_t, detect_contacts
  use voussoir_contact_law, only: contact_law_t
  use voussoir_nlgs, only: nlgs_work_t, nlgs_prepare, nlgs_solve, warm_start
  use voussoir_contact_rows, only: apply_impulse_change
  use voussoir_motion, only: motion_t, motion_eval, motion_eval_vertical, waveform_ramp, vertical_none
  use voussoir_coarse, only: coarse_t
  implicit none
  private

  public :: model_t, solver_settings_t, model_step, model_rest_step, model_apply_impulses

  !> Numerical settings of the time stepping and of the contact solve.
  type :: solver_settings_t
    real(dp) :: dt_s = 1.0e-3_dp
    real(dp) :: theta = 0.5_dp
    real(dp) :: tol = 1.0e-4_dp
    integer :: max_iter = 10000
    real(dp) :: alert_m = 0.0_dp              !! 0: automatic, as in the config
    logical :: allow_nonconvergence = .false.
    real(dp) :: rest_capacity_m_s2 = 0.0_dp   !! see the config's; 0: every step is solved
  end type solver_settings_t

  !> Everything one simulation evolves.
  type :: model_t
    type(bodies_t) :: bodies
    type(contact_set_t) :: contacts
    type(nlgs_work_t) :: work
    type(motion_t) :: motion
    type(solver_settings_t) :: solver
    type(contact_law_t) :: law
    type(coarse_t) :: coarse            !! the courses of a wall (none: plain NLGS)
    real(dp) :: t_s = 0.0_dp
    integer :: step = 0
    ! Of the last step:
    integer :: iterations = 0
    real(dp) :: norm = 0.0_dp
    logical :: converged = .true.
    integer :: nonconverged_steps = 0
    real(dp) :: table(3) = 0.0_dp       !! table x [m], v [m/s], a [m/s2] at t_s
    real(dp) :: table_vertical(3) = 0.0_dp !! table y [m], v [m/s], a [m/s2] at t_s, upwards
    real(dp), allocatable :: q_pred(:, :), v_free(:, :)
  end type model_t

contains

  !> Advance `model` by one time step.
  subroutine model_step(model, status)
    type(model_t), intent(inout) :: model
    type(status_t), intent(inout) :: status
    real(dp) :: h, theta, x0, v0, a0, x1, v1, a1, load_x, speed, y0, vy0, ay0, y1, vy1, ay1
    integer :: i, nb
    character(len=160) :: where

    h = model%solver%dt_s
    theta = model%solver%theta
    nb = model%bodies%n
    if (.not. allocated(model%q_pred)) allocate (model%q_pred(3, nb), model%v_free(3, nb))

    call motion_eval(model%motion, model%t_s, x0, v0, a0)
    call motion_eval(model%motion, model%t_s + h, x1, v1, a1)
    call motion_eval_vertical(model%motion, model%t_s, y0, vy0, ay0)
    call motion_eval_vertical(model%motion, model%t_s + h, y1, vy1, ay1)
    ! Inertial load of the ramp, at the theta point of the step.
    load_x = 0.0_dp
    if (model%motion%waveform == waveform_ramp) load_x = (1.0_dp - theta)*a0 + theta*a1

    associate (b => model%bodies)
      do i = 1, nb
        if (b%driven(i)) then
          b%v(:, i) = [v0, vy0, 0.0_dp]
          model%v_free(:, i) = [v1, vy1, 0.0_dp]
        else
          ! Gravity, the inertial load and the constant loads of &load (at the step's start).
          model%v_free(:, i) = b%v(:, i) + h*([load_x, -g_m_s2, 0.0_dp] + &
                               [b%inv_mass(i), b%inv_mass(i), b%inv_inertia(i)]*external_load(b, i, b%q(3, i)))
        end if
      end do
      call advance(model%q_pred, b%q, (1.0_dp - theta)*h, b%v)
      call update_world_vertices(b, model%q_pred)
      call detect_contacts(b, model%q_pred, model%solver%alert_m, model%law, model%contacts)
      call nlgs_prepare(b, model%contacts, theta*h, model%work)
      call warm_start(model%work, model%contacts, nb, remember=.false.)
      b%v = model%v_free
      call model_apply_impulses(model)
      call nlgs_solve(model%contacts, model%work, b%v, model%solver%tol, model%solver%max_iter, &
                      model%iterations, model%norm, model%converged, model%coarse)
      call warm_start(model%work, model%contacts, nb, remember=.true.)
    end associate

    model%step = model%step + 1
    speed = largest_speed(model%bodies%v)
    if (.not. (model%norm == model%norm) .or. .not. (speed == speed)) then
      call fail(status, 'NaN in the contact solve at '//where_now())
      return
    end if
    if (speed > 1.0e6_dp) then
      call fail(status, 'divergence (velocity above 1e6 m/s) at '//where_now())
      return
    end if
    if (.not. model%converged) then
      model%nonconverged_steps = model%nonconverged_steps + 1
      if (.not. model%solver%allow_nonconvergence) then
        write (where, '(a,a,i0,a,es10.3,a,es10.3)') where_now(), ': ', model%iterations, &
          ' iterations, norm ', model%norm, ' > tol ', model%solver%tol
        call fail(status, 'NLGS did not converge at '//trim(where)// &
                  ' (raise max_iter or set allow_nonconvergence = .true. in &solver)')
        return
      end if
    end if

    call advance(model%bodies%q, model%q_pred, theta*h, model%bodies%v)
    ! The table's displacement is known exactly: keep the driven bodies on it rather than
    ! on the theta-rule integral of its velocity (which differs by O(h^3) per step).
    where (model%bodies%driven) model%bodies%q(1, :) = model%bodies%q_ref(1, :) + x1
    if (model%motion%vertical /= vertical_none) then
      where (model%bodies%driven) model%bodies%q(2, :) = model%bodies%q_ref(2, :) + y1
      model%table_vertical = [y1, vy1, ay1]
    end if
    model%t_s = model%t_s + h
    model%table = [x1, v1, a1]
    if (model%motion%waveform == waveform_ramp) model%table = [0.0_dp, 0.0_dp, a1]

  contains

    !> Where the step is, for messages (formatted only when one is needed).
    function where_now() result(text)
      character(len=:), allocatable :: text
      character(len=64) :: buf
      write (buf, '(a,i0,a,es12.5,a)') 'step ', model%step, ' (t = ', model%t_s + h, ' s)'
      text = trim(buf)
    end function where_now
  end subroutine model_step

  !> Advance `model` by one time step in which its free bodies ride on the table as one
  !> rigid body, at rest on it (voussoir_simulation decides when that holds): they move
  !> by the table's displacement over the step and take its velocity; no contact is
  !> solved (0 iterations).
  subroutine model_rest_step(model)
    type(model_t), intent(inout) :: model
    real(dp) :: h, x0, v0, a0, x1, v1, a1
    h = model%solver%dt_s
    call motion_eval(model%motion, model%t_s, x0, v0, a0)
    call motion_eval(model%motion, model%t_s + h, x1, v1, a1)
    model%bodies%q(1, :) = model%bodies%q(1, :) + (x1 - x0)
    where (model%bodies%driven) model%bodies%q(1, :) = model%bodies%q_ref(1, :) + x1
    model%bodies%v(1, :) = v1
    model%bodies%v(2:3, :) = 0.0_dp
    model%step = model%step + 1
    model%t_s = model%t_s + h
    model%iterations = 0
    model%norm = 0.0_dp
    model%converged = .true.
    model%table = [x1, v1, a1]
  end subroutine model_rest_step

  !> q_new = q + h_part v, element by element (the same operations as the array
  !> expression q + h_part*v, without its temporary).
  pure subroutine advance(q_new, q, h_part, v)
    real(dp), intent(out) :: q_new(:, :)
    real(dp), intent(in) :: q(:, :), h_part, v(:, :)
    integer :: i
    do i = 1, size(q, 2)
      q_new(1, i) = q(1, i) + h_part*v(1, i)
      q_new(2, i) = q(2, i) + h_part*v(2, i)
      q_new(3, i) = q(3, i) + h_part*v(3, i)
    end do
  end subroutine advance

  !> The largest |component| of the velocities `v` (3, n) [m/s, rad/s]; NaN if any is NaN.
  pure function largest_speed(v) result(speed)
    real(dp), intent(in) :: v(:, :)
    real(dp) :: speed
    integer :: i, j
    speed = 0.0_dp
    do i = 1, size(v, 2)
      do j = 1, 3
        if (.not. (v(j, i) == v(j, i))) then
          speed = v(j, i)
          return
        end if
        speed = max(speed, abs(v(j, i)))
      end do
    end do
  end function largest_speed

  !> Velocities of the free bodies plus the effect of the impulses held in the contacts
  !> (their packed data prepared by nlgs_prepare).
  subroutine model_apply_impulses(model)
    type(model_t), intent(inout) :: model
    integer :: k
    associate (c => model%contacts, bd => model%bodies, w => model%work)
      do k = 1, c%n
        if (c%impulse(1, k) == 0.0_dp .and. c%impulse(2, k) == 0.0_dp) cycle
        call apply_impulse_change(w%data(:, k), c%impulse(1, k), c%impulse(2, k), bd%v(:, c%body_a(k)), &
                                  bd%v(:, c%body_b(k)))
      end do
    end associate
  end subroutine model_apply_impulses

end module voussoir_model
