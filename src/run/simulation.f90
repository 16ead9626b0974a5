!> A whole run: the time loop, the monitors it updates (voussoir_monitors) and its record.
module voussoir_simulation
  use, intrinsic :: iso_fortran_env, only: int64
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t
  use voussoir_model, only: model_t, model_step, model_rest_step
  use voussoir_motion, only: waveform_ramp
  use voussoir_rest_window, only: rest_window_t, rest_window, relative_speed, smallest_free_size, &
                                  still_speed_m_s, still_s, drift_fraction
  use voussoir_model, only: model_t, model_step
  use voussoir_motion, only: vertical_none
  use voussoir_monitors, only: monitor_t, monitor_clear, monitor_update, crown_displacement, residual_displacement, &
                               joint_of_pair
  use voussoir_contacts, only: contact_set_t
  use voussoir_interrupt, only: stop_signal
  implicit none
  private

  public :: run_result_t, simulate

  !> The record of a run.
  type :: run_result_t
    integer :: n_samples = 0
    real(dp), allocatable :: time_s(:), table(:, :), crown(:, :), q(:, :, :)
    real(dp), allocatable :: table_vertical(:, :)   !! (3, :) y, v, a upwards; only with a vertical motion
    integer, allocatable :: contact_count(:)
    logical :: contacts_recorded = .false.   !! whether the contact record below was kept
    !> The contacts that carry load (normal impulse > 0) at each sample, one flat list:
    !> those of sample s are entries contact_start(s) .. contact_start(s + 1) - 1; the
    !> arrays may be longer than n_contact_records (room reserved, not trimmed).
    integer :: n_contact_records = 0
    integer, allocatable :: contact_start(:)         !! (n_samples + 1)
    integer, allocatable :: contact_bodies(:, :)     !! (2, :) candidate a, antagonist b
    integer, allocatable :: contact_joint(:)         !! arch joint 0..n, -1 when none
    real(dp), allocatable :: contact_point(:, :)     !! (2, :) [m]
    real(dp), allocatable :: contact_normal(:, :)    !! (2, :) unit, from b towards a
    real(dp), allocatable :: contact_impulse(:, :)   !! (2, :) of the step on a [N s]: tangent, normal
    integer :: n_steps = 0
    real(dp), allocatable :: step_time_s(:), step_norm(:)
    integer, allocatable :: step_iterations(:)
    integer :: n_hinges = 0
    real(dp), allocatable :: hinge_time_s(:)
    integer, allocatable :: hinge_joint(:), hinge_side(:)
    logical :: collapsed = .false.
    real(dp) :: collapse_time_s = 0.0_dp
    integer :: interrupted_by = 0        !! the signal that stopped the run early (0: it ran to its end)
    real(dp) :: peak_crown_disp_m = 0.0_dp
    !> Where the free blocks ended up: the largest displacement of one of them relative to
    !> the table at the end of the run [m], and which (a wall that slid has not just "stood").
    real(dp) :: max_residual_disp_m = 0.0_dp
    integer :: max_residual_body = 0
    !> The largest opening of an arch joint during the run [m] (0 when not an arch), and
    !> the crown's horizontal displacement relative to the table at its end [m], signed.
    real(dp) :: peak_joint_opening_m = 0.0_dp
    real(dp) :: residual_crown_drift_m = 0.0_dp
    real(dp) :: mean_iterations = 0.0_dp
    integer :: max_iterations = 0
    integer :: nonconverged_steps = 0
    !> Steps not solved because the assembly rode at rest on the table (the model's
    !> rest_capacity_m_s2; voussoir_rest_window), and whether the run ended at rest
    !> before its motion did.
    integer :: rest_steps = 0
    logical :: ended_at_rest = .false.
    real(dp) :: wall_time_s = 0.0_dp
  end type run_result_t

contains

  !> Run `model` for `duration_s`, sampling every `every` steps, watched by `mon` (cleared
  !> first); stop `stop_after_collapse_s` after a collapse (never when negative). With
  !> `record_contacts` the loaded contacts of every sample are kept (a result file's
  !> /contacts); a sweep, which keeps only the outcome, goes without. With a static
  !> capacity in the model's settings (rest_capacity_m_s2 > 0; not for a ramp nor with a
  !> vertical table motion), the steps
  !> in which the assembly rides at rest on the table are not solved, and the run ends
  !> once it has settled after its motion's last strong part (voussoir_rest_window).
  subroutine simulate(model, mon, duration_s, every, stop_after_collapse_s, res, status, record_contacts)
    type(model_t), intent(inout) :: model
    type(monitor_t), intent(inout) :: mon
    real(dp), intent(in) :: duration_s, stop_after_collapse_s
    integer, intent(in) :: every
    type(run_result_t), intent(out) :: res
    type(status_t), intent(inout) :: status
    logical, intent(in), optional :: record_contacts
    integer :: n_steps, n_samples, nb, istep
    integer(8) :: clock0, clock1, rate
    real(dp) :: sum_iter, still_for_s, crown_end_m(2)
    type(rest_window_t) :: window

    call system_clock(clock0, rate)
    nb = model%bodies%n
    n_steps = max(1, nint(duration_s/model%solver%dt_s))
    n_samples = n_steps/every + 2  ! t = 0, every multiple of `every`, and the last step
    allocate (res%time_s(n_samples), res%table(3, n_samples), res%crown(2, n_samples), &
              res%q(3, nb, n_samples), res%contact_count(n_samples), res%step_time_s(n_steps), &
              res%step_norm(n_steps), res%step_iterations(n_steps), res%contact_start(n_samples + 1))
    res%contact_start(1) = 1
    if (present(record_contacts)) res%contacts_recorded = record_contacts
    call monitor_clear(mon)
    call add_sample(res, model, mon)
    sum_iter = 0.0_dp
    ! Not with a vertical table motion: the capacity is that of gravity alone.
    if (model%motion%waveform /= waveform_ramp .and. model%motion%vertical == vertical_none) &
      window = rest_window(model%motion, model%solver%dt_s, n_steps, model%solver%rest_capacity_m_s2)
    still_for_s = 0.0_dp
    do istep = 1, n_steps
      if (istep <= window%lead_steps) then
        call model_rest_step(model)
        res%rest_steps = res%rest_steps + 1
      else
        call model_step(model, status)
      end if
      if (.not. status%ok) exit
      res%n_steps = istep
      res%step_time_s(istep) = model%t_s
      res%step_iterations(istep) = model%iterations
      res%step_norm(istep) = model%norm
      sum_iter = sum_iter + model%iterations
      call monitor_update(mon, model%bodies, model%t_s)
      if (modulo(istep, every) == 0) call add_sample(res, model, mon)
      if (mon%collapsed .and. stop_after_collapse_s >= 0.0_dp) then
        if (model%t_s >= mon%collapse_time_s + stop_after_collapse_s) exit
      end if
      res%interrupted_by = stop_signal()
      if (res%interrupted_by /= 0) exit
      if (istep > window%tail_step .and. .not. mon%collapsed) then
        res%ended_at_rest = settled(model, mon, still_for_s)
        if (res%ended_at_rest) exit
      end if
    end do
    if (res%n_steps > 0) then
      if (modulo(res%n_steps, every) /= 0) call add_sample(res, model, mon)
      res%mean_iterations = sum_iter/res%n_steps
      res%max_iterations = maxval(res%step_iterations(1:res%n_steps))
    end if
    res%nonconverged_steps = model%nonconverged_steps
    call residual_displacement(mon, model%bodies, res%max_residual_disp_m, res%max_residual_body)
    crown_end_m = crown_displacement(mon, model%bodies)
    res%residual_crown_drift_m = crown_end_m(1)
    call close_record(res, mon)
    call system_clock(clock1)
    res%wall_time_s = real(clock1 - clock0, dp)/real(rate, dp)
  end subroutine simulate

  !> Whether the free blocks of `model` have been still on the table for `still_s`
  !> (`still_for_s` counts the time so far) and stand where they were built.
  logical function settled(model, mon, still_for_s)
    type(model_t), intent(in) :: model
    type(monitor_t), intent(in) :: mon
    real(dp), intent(inout) :: still_for_s
    real(dp) :: drift_m
    integer :: body
    settled = .false.
    if (relative_speed(model%bodies, model%table(2)) >= still_speed_m_s) then
      still_for_s = 0.0_dp
      return
    end if
    still_for_s = still_for_s + model%solver%dt_s
    if (still_for_s < still_s) return
    call residual_displacement(mon, model%bodies, drift_m, body)
    settled = drift_m <= drift_fraction*smallest_free_size(model%bodies)
  end function settled

  !> Add the present state of `model` to the samples of `res`.
  subroutine add_sample(res, model, mon)
    type(run_result_t), intent(inout) :: res
    type(model_t), intent(in) :: model
    type(monitor_t), intent(in) :: mon
    integer :: s
    res%n_samples = res%n_samples + 1
    s = res%n_samples
    res%time_s(s) = model%t_s
    res%table(:, s) = model%table
    if (model%motion%vertical /= vertical_none) then
      if (.not. allocated(res%table_vertical)) allocate (res%table_vertical(3, size(res%time_s)))
      res%table_vertical(:, s) = model%table_vertical
    end if
    res%crown(:, s) = crown_displacement(mon, model%bodies)
    res%q(:, :, s) = model%bodies%q
    if (res%contacts_recorded) then
      call add_contacts(res, model%contacts, mon)
      res%contact_count(s) = res%n_contact_records + 1 - res%contact_start(s)
    else
      res%contact_start(s + 1) = res%contact_start(s)
      res%contact_count(s) = 0
      if (model%contacts%n > 0) &
        res%contact_count(s) = count(model%contacts%impulse(2, 1:model%contacts%n) > 0.0_dp)
    end if
  end subroutine add_sample

  !> Append the contacts of `set` that carry load (normal impulse > 0) to the record of
  !> the newest sample of `res`, named by their bodies and (arches) joint.
  subroutine add_contacts(res, set, mon)
    type(run_result_t), intent(inout) :: res
    type(contact_set_t), intent(in) :: set
    type(monitor_t), intent(in) :: mon
    integer, parameter :: max_projected = 2**25   ! records reserved ahead at most (2 GB)
    integer :: k, m, n_new
    integer(int64) :: projected
    n_new = 0
    if (set%n > 0) n_new = count(set%impulse(2, 1:set%n) > 0.0_dp)
    ! Room for the rest of the run at this sample's count: memory that is reserved but
    ! never written costs nothing, and copying on growth is what a long run pays for.
    projected = res%n_contact_records + int(n_new, int64)*(size(res%time_s) - res%n_samples + 1)
    call reserve_contacts(res, res%n_contact_records + n_new, int(min(projected, int(max_projected, int64))))
    m = res%n_contact_records
    do k = 1, set%n
      if (.not. set%impulse(2, k) > 0.0_dp) cycle
      m = m + 1
      res%contact_bodies(:, m) = [set%body_a(k), set%body_b(k)]
      res%contact_joint(m) = joint_of_pair(mon, set%body_a(k), set%body_b(k))
      res%contact_point(:, m) = set%point(:, k)
      res%contact_normal(:, m) = set%normal(:, k)
      res%contact_impulse(:, m) = set%impulse(:, k)
    end do
    res%n_contact_records = m
    res%contact_start(res%n_samples + 1) = m + 1
  end subroutine add_contacts

  !> Room for `capacity` contact records in `res`, the present ones kept: when it must
  !> grow, to `projected` or twice `capacity`, whichever is larger.
  subroutine reserve_contacts(res, capacity, projected)
    type(run_result_t), intent(inout) :: res
    integer, intent(in) :: capacity, projected
    integer :: new_cap, m
    integer, allocatable :: bodies(:, :), joint(:)
    real(dp), allocatable :: point(:, :), normal(:, :), impulse(:, :)
    if (allocated(res%contact_joint)) then
      if (size(res%contact_joint) >= capacity) return
    end if
    new_cap = max(256, 2*capacity, projected)
    m = res%n_contact_records
    allocate (bodies(2, new_cap), joint(new_cap), point(2, new_cap), normal(2, new_cap), impulse(2, new_cap))
    if (m > 0) then
      bodies(:, 1:m) = res%contact_bodies(:, 1:m)
      joint(1:m) = res%contact_joint(1:m)
      point(:, 1:m) = res%contact_point(:, 1:m)
      normal(:, 1:m) = res%contact_normal(:, 1:m)
      impulse(:, 1:m) = res%contact_impulse(:, 1:m)
    end if
    call move_alloc(bodies, res%contact_bodies)
    call move_alloc(joint, res%contact_joint)
    call move_alloc(point, res%contact_point)
    call move_alloc(normal, res%contact_normal)
    call move_alloc(impulse, res%contact_impulse)
  end subroutine reserve_contacts

  !> Cut the record to the samples and steps made, and copy what the monitors saw.
  subroutine close_record(res, mon)
    type(run_result_t), intent(inout) :: res
    type(monitor_t), intent(in) :: mon
    res%time_s = res%time_s(1:res%n_samples)
    res%table = res%table(:, 1:res%n_samples)
    if (allocated(res%table_vertical)) res%table_vertical = res%table_vertical(:, 1:res%n_samples)
    res%crown = res%crown(:, 1:res%n_samples)
    res%q = res%q(:, :, 1:res%n_samples)
    res%contact_count = res%contact_count(1:res%n_samples)
    res%contact_start = res%contact_start(1:res%n_samples + 1)
    call reserve_contacts(res, 0, 0)
    res%step_time_s = res%step_time_s(1:res%n_steps)
    res%step_norm = res%step_norm(1:res%n_steps)
    res%step_iterations = res%step_iterations(1:res%n_steps)
    res%collapsed = mon%collapsed
    res%collapse_time_s = mon%collapse_time_s
    res%peak_crown_disp_m = mon%peak_crown_disp_m
    res%peak_joint_opening_m = mon%peak_joint_opening_m
    res%n_hinges = mon%n_hinges
    res%hinge_time_s = mon%hinge_time_s(1:mon%n_hinges)
    res%hinge_joint = mon%hinge_joint(1:mon%n_hinges)
    res%hinge_side = mon%hinge_side(1:mon%n_hinges)
  end subroutine close_record

end module voussoir_simulation
