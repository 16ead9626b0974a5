!> The jobs of a sweep plan: which parameter set, frequency, amplitude or record a job
!> index stands for, the configuration of one of its runs, its search and its cost
!> (job layout: docs/sweep.md).
module voussoir_sweep_jobs
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t
  use voussoir_text, only: itoa
  use voussoir_config, only: config_t, fmt_real
  use voussoir_threshold_search, only: threshold_search_t, threshold_init_onset
  use voussoir_threshold, only: search_run_config, threshold_init, static_capacity_m_s2
  use voussoir_sweep_plan, only: sweep_plan_t
  implicit none
  private

  public :: job_param_set, job_frequency_hz, job_amplitude_m, job_run_config, job_cost, job_record, &
            job_search_init, job_label

contains

  !> Record (1-based, into plan%records) of an IDA job.
  pure integer function job_record(plan, job)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    job_record = modulo(job, plan%records%n) + 1
  end function job_record

  !> What job `job` is, for messages: its parameter set and frequency or record.
  function job_label(plan, job) result(text)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    character(len=:), allocatable :: text
    text = 'job '//itoa(job)//' (parameter set '//itoa(job_param_set(plan, job))//', '
    if (plan%mode == 'ida') then
      text = text//'record '//trim(plan%records%given(job_record(plan, job)))//')'
    else
      text = text//fmt_real(job_frequency_hz(plan, job))//' Hz)'
    end if
  end function job_label

  !> A new search for job `job` (threshold and ida modes). An IDA search starts from
  !> the scale at which the record's PGA equals the arch's static capacity lambda g.
  subroutine job_search_init(plan, job, search, status)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    type(threshold_search_t), intent(out) :: search
    type(status_t), intent(inout) :: status
    associate (c => plan%set_cfg(job_param_set(plan, job)))
      if (plan%mode == 'ida') then
        call threshold_init_onset(search, c, static_capacity_m_s2(c)/plan%records%pga_m_s2(job_record(plan, job)), &
                                  plan%search, status)
      else
        call threshold_init(search, c, job_frequency_hz(plan, job), plan%search, status)
      end if
    end associate
  end subroutine job_search_init

  !> Parameter set (0-based) of job `job` (0-based).
  pure integer function job_param_set(plan, job)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    job_param_set = job/(plan%n_freq_per_set*plan%n_amp)
  end function job_param_set

  pure real(dp) function job_frequency_hz(plan, job)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    if (plan%mode == 'ida') then
      job_frequency_hz = 0.0_dp
    else if (plan%pair_frequencies) then
      job_frequency_hz = plan%frequencies_hz(job_param_set(plan, job) + 1)
    else
      job_frequency_hz = plan%frequencies_hz(modulo(job/plan%n_amp, plan%n_freq) + 1)
    end if
  end function job_frequency_hz

  !> Commanded amplitude of a grid job (0 in threshold mode).
  pure real(dp) function job_amplitude_m(plan, job)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    job_amplitude_m = 0.0_dp
    if (plan%mode == 'grid') job_amplitude_m = plan%amplitudes_m(modulo(job, plan%n_amp) + 1)
  end function job_amplitude_m

  !> The configuration of one run of job `job` at `amplitude_m` (ida: the scale of its
  !> record): a search run stops at the collapse; a grid run keeps the base case's
  !> stop_after_collapse_s. No time series is kept.
  pure function job_run_config(plan, job, amplitude_m) result(cfg)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    real(dp), intent(in) :: amplitude_m
    type(config_t) :: cfg
    cfg = search_run_config(plan%set_cfg(job_param_set(plan, job)), job_frequency_hz(plan, job), amplitude_m)
    if (plan%mode == 'ida') then
      cfg%motion%waveform = 'accelerogram'
      cfg%motion%record_file = plan%records%files(job_record(plan, job))
      cfg%motion%record_scale = amplitude_m
      cfg%motion%amplitude_m = 0.0_dp
    end if
    if (plan%mode == 'grid') cfg%output%stop_after_collapse_s = &
      plan%set_cfg(job_param_set(plan, job))%output%stop_after_collapse_s
  end function job_run_config

  !> Relative cost of one run of job `job`: steps x bodies.
  pure real(dp) function job_cost(plan, job)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    real(dp) :: duration_s, f_hz
    f_hz = job_frequency_hz(plan, job)
    associate (c => plan%set_cfg(job_param_set(plan, job)))
      duration_s = c%motion%duration_s
      if (duration_s == 0.0_dp .and. plan%mode == 'ida') then
        duration_s = c%motion%rest_s + plan%records%duration_s(job_record(plan, job))
      else if (duration_s == 0.0_dp) then
        duration_s = (c%motion%n_attack + c%motion%n_full + c%motion%n_decay)/f_hz + c%motion%rest_s
      end if
      job_cost = duration_s/c%solver%dt_s*(c%arch%n_voussoirs + 2)
    end associate
  end function job_cost

end module voussoir_sweep_jobs
