!> A whole run: the time loop, the monitors it updates (voussoir_monitors) and its record.
module voussoir_simulation
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t
  use voussoir_model, only: model_t, model_step
  use voussoir_monitors, only: monitor_t, monitor_clear, monitor_update, crown_displacement, residual_displacement
  use voussoir_interrupt, only: stop_signal
  implicit none
  private

  public :: run_result_t, simulate

  !> The record of a run.
  type :: run_result_t
    integer :: n_samples = 0
    real(dp), allocatable :: time_s(:), table(:, :), crown(:, :), q(:, :, :)
    integer, allocatable :: contact_count(:)
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
    real(dp) :: mean_iterations = 0.0_dp
    integer :: max_iterations = 0
    integer :: nonconverged_steps = 0
    real(dp) :: wall_time_s = 0.0_dp
  end type run_result_t

contains

  !> Run `model` for `duration_s`, sampling every `every` steps, watched by `mon` (cleared
  !> first); stop `stop_after_collapse_s` after a collapse (never when negative).
  subroutine simulate(model, mon, duration_s, every, stop_after_collapse_s, res, status)
    type(model_t), intent(inout) :: model
    type(monitor_t), intent(inout) :: mon
    real(dp), intent(in) :: duration_s, stop_after_collapse_s
    integer, intent(in) :: every
    type(run_result_t), intent(out) :: res
    type(status_t), intent(inout) :: status
    integer :: n_steps, n_samples, nb, istep
    integer(8) :: clock0, clock1, rate
    real(dp) :: sum_iter

    call system_clock(clock0, rate)
    nb = model%bodies%n
    n_steps = max(1, nint(duration_s/model%solver%dt_s))
    n_samples = n_steps/every + 2  ! t = 0, every multiple of `every`, and the last step
    allocate (res%time_s(n_samples), res%table(3, n_samples), res%crown(2, n_samples), &
              res%q(3, nb, n_samples), res%contact_count(n_samples), res%step_time_s(n_steps), &
              res%step_norm(n_steps), res%step_iterations(n_steps))
    call monitor_clear(mon)
    call add_sample(res, model, mon)
    sum_iter = 0.0_dp
    do istep = 1, n_steps
      call model_step(model, status)
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
    end do
    if (res%n_steps > 0) then
      if (modulo(res%n_steps, every) /= 0) call add_sample(res, model, mon)
      res%mean_iterations = sum_iter/res%n_steps
      res%max_iterations = maxval(res%step_iterations(1:res%n_steps))
    end if
    res%nonconverged_steps = model%nonconverged_steps
    call residual_displacement(mon, model%bodies, res%max_residual_disp_m, res%max_residual_body)
    call close_record(res, mon)
    call system_clock(clock1)
    res%wall_time_s = real(clock1 - clock0, dp)/real(rate, dp)
  end subroutine simulate

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
    res%crown(:, s) = crown_displacement(mon, model%bodies)
    res%q(:, :, s) = model%bodies%q
    res%contact_count(s) = 0
    if (model%contacts%n > 0) &
      res%contact_count(s) = count(model%contacts%impulse(2, 1:model%contacts%n) > 0.0_dp)
  end subroutine add_sample

  !> Cut the record to the samples and steps made, and copy what the monitors saw.
  subroutine close_record(res, mon)
    type(run_result_t), intent(inout) :: res
    type(monitor_t), intent(in) :: mon
    res%time_s = res%time_s(1:res%n_samples)
    res%table = res%table(:, 1:res%n_samples)
    res%crown = res%crown(:, 1:res%n_samples)
    res%q = res%q(:, :, 1:res%n_samples)
    res%contact_count = res%contact_count(1:res%n_samples)
    res%step_time_s = res%step_time_s(1:res%n_steps)
    res%step_norm = res%step_norm(1:res%n_steps)
    res%step_iterations = res%step_iterations(1:res%n_steps)
    res%collapsed = mon%collapsed
    res%collapse_time_s = mon%collapse_time_s
    res%peak_crown_disp_m = mon%peak_crown_disp_m
    res%n_hinges = mon%n_hinges
    res%hinge_time_s = mon%hinge_time_s(1:mon%n_hinges)
    res%hinge_joint = mon%hinge_joint(1:mon%n_hinges)
    res%hinge_side = mon%hinge_side(1:mon%n_hinges)
  end subroutine close_record

end module voussoir_simulation
