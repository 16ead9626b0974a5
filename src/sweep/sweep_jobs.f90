!> The jobs of a sweep plan, whatever its mode: which parameter set a job index stands
!> for, and what the plan's mode says of it (its frequency or value, the configuration
!> of one of its runs, its search, its cost, its label). Job layout: docs/sweep.md.
module voussoir_sweep_jobs
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t
  use voussoir_text, only: itoa
  use voussoir_config, only: config_t
  use voussoir_threshold_search, only: threshold_search_t
  use voussoir_sweep_mode, only: sweep_plan_t, job_param_set
  implicit none
  private

  public :: job_param_set, job_frequency_hz, job_amplitude_m, job_run_config, job_cost, job_search_init, job_label

contains

  !> What job `job` is, for messages: its parameter set and frequency or record.
  function job_label(plan, job) result(text)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    character(len=:), allocatable :: text
    text = 'job '//itoa(job)//' (parameter set '//itoa(job_param_set(plan, job))//', '// &
           plan%mode%job_label(plan, job)//')'
  end function job_label

  !> A new search for job `job` (modes whose jobs are searches).
  subroutine job_search_init(plan, job, search, status)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    type(threshold_search_t), intent(out) :: search
    type(status_t), intent(inout) :: status
    call plan%mode%search_init(plan, job, search, status)
  end subroutine job_search_init

  !> Table frequency of job `job` [Hz] (0 in a mode without one).
  pure real(dp) function job_frequency_hz(plan, job)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    job_frequency_hz = plan%mode%frequency_hz(plan, job)
  end function job_frequency_hz

  !> Commanded amplitude of a job that is one run (0 for a search).
  pure real(dp) function job_amplitude_m(plan, job)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    job_amplitude_m = plan%mode%run_value(plan, job)
  end function job_amplitude_m

  !> The configuration of one run of job `job` at `amplitude_m` (ida: the scale of its
  !> record). No time series is kept.
  pure function job_run_config(plan, job, amplitude_m) result(cfg)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    real(dp), intent(in) :: amplitude_m
    type(config_t) :: cfg
    cfg = plan%mode%run_config(plan, job, amplitude_m)
  end function job_run_config

  !> Relative cost of one run of job `job`: steps x bodies.
  pure real(dp) function job_cost(plan, job)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    job_cost = plan%mode%cost(plan, job)
  end function job_cost

end module voussoir_sweep_jobs
