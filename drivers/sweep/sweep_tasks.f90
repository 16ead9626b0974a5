!> The tasks of a sweep: one simulation of a job, and the messages between ranks.
!>
!> Message layouts (reals): a task is [job, run, amplitude_m, n, then n x (amplitude_m,
!> collapsed, peak_crown_disp_m) of the search's earlier runs]; a result is
!> [job, run, continuing, then the outcome (its fields in the order of run_outcome_t)].
module voussoir_sweep_tasks
  use, intrinsic :: iso_fortran_env, only: output_unit
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t
  use voussoir_text, only: fmt_real
  use voussoir_assembly, only: assembly_t
  use voussoir_model, only: model_t
  use voussoir_simulation, only: run_result_t
  use voussoir_setup, only: run_config
  use voussoir_threshold_search, only: run_outcome_t
  use voussoir_threshold, only: outcome_of_run
  use voussoir_sweep_plan, only: sweep_plan_t
  use voussoir_sweep_jobs, only: job_label, job_run_config
  implicit none
  private

  public :: queued_task_t, simulate_job, msg_of_outcome, outcome_of_msg
  public :: prefetch, task_head, history_width, result_len

  integer, parameter :: prefetch = 2                        !! tasks a worker may hold
  integer, parameter :: task_head = 4, history_width = 3, result_len = 14

  !> A task waiting on a worker.
  type :: queued_task_t
    real(dp), allocatable :: msg(:)
  end type queued_task_t

contains

  !> One simulation of job `job` at `amp_m` (ida: the scale of its record). A run that
  !> stops with an error (e.g. a step without NLGS convergence) is an outcome too,
  !> `o%failed`: its reason, labelled with the job, is printed as a warning and the sweep
  !> goes on (`status` stays ok).
  subroutine simulate_job(plan, job, amp_m, o, status)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    real(dp), intent(in) :: amp_m
    type(run_outcome_t), intent(out) :: o
    type(status_t), intent(inout) :: status
    type(assembly_t) :: assembly
    type(model_t) :: model
    type(run_result_t) :: res
    call run_config(job_run_config(plan, job, amp_m), assembly, model, res, status)
    if (.not. status%ok) then
      write (output_unit, '(a)') 'voussoir-sweep: warning: run failed, recorded as such: '//job_label(plan, job)// &
        ' at '//plan%mode%value_name()//' '//fmt_real(amp_m)//': '// &
        trim(status%message)
      flush (output_unit)
      status = status_t()
      o%amplitude_m = amp_m
      o%failed = .true.
      o%collapse_time_s = ieee_value(1.0_dp, ieee_quiet_nan)
      o%peak_crown_disp_m = o%collapse_time_s
      o%peak_joint_opening_m = o%collapse_time_s
      o%residual_crown_drift_m = o%collapse_time_s
      o%mean_iterations = o%collapse_time_s
      return
    end if
    o = outcome_of_run(amp_m, res)
  end subroutine simulate_job

  pure function msg_of_outcome(job, seq, continuing, o) result(msg)
    integer, intent(in) :: job, seq
    logical, intent(in) :: continuing
    type(run_outcome_t), intent(in) :: o
    real(dp) :: msg(result_len)
    msg = [real(job, dp), real(seq, dp), merge(1.0_dp, 0.0_dp, continuing), o%amplitude_m, &
           merge(1.0_dp, 0.0_dp, o%collapsed), o%collapse_time_s, o%peak_crown_disp_m, o%mean_iterations, &
           real(o%n_steps, dp), real(o%nonconverged_steps, dp), o%wall_time_s, merge(1.0_dp, 0.0_dp, o%failed), &
           o%peak_joint_opening_m, o%residual_crown_drift_m]
  end function msg_of_outcome

  pure function outcome_of_msg(msg) result(o)
    real(dp), intent(in) :: msg(result_len)
    type(run_outcome_t) :: o
    o%amplitude_m = msg(4)
    o%collapsed = msg(5) == 1.0_dp
    o%collapse_time_s = msg(6)
    o%peak_crown_disp_m = msg(7)
    o%mean_iterations = msg(8)
    o%n_steps = nint(msg(9))
    o%nonconverged_steps = nint(msg(10))
    o%wall_time_s = msg(11)
    o%failed = msg(12) == 1.0_dp
    o%peak_joint_opening_m = msg(13)
    o%residual_crown_drift_m = msg(14)
  end function outcome_of_msg

end module voussoir_sweep_tasks
