!> What the modes that drive the table with the `afd` waveform share (threshold and
!> grid): a job is a parameter set at a frequency of `frequencies_hz` (all of them, or
!> its own with `pair_frequencies`), the record variables of an IDA are refused, and each
!> run is the base case's afd motion at the job's frequency and an amplitude. A mode over
!> afd frequencies extends `afd_mode_t` and says what it does with the amplitudes.
module voussoir_sweep_mode_afd
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa, fmt_real, fmt_exact_list
  use voussoir_config, only: config_t, waveform_afd
  use voussoir_input_range, only: need
  use voussoir_threshold, only: search_run_config
  use voussoir_sweep_group, only: sweep_group_t, unset_real
  use voussoir_sweep_table, only: named_values_t, named_text_t
  use voussoir_sweep_mode, only: sweep_mode_t, sweep_plan_t, job_param_set, run_bodies
  implicit none
  private

  public :: afd_mode_t, afd_jobs_text, afd_run_config, afd_file_items

  !> A mode over the frequencies of the afd waveform.
  type, abstract, extends(sweep_mode_t) :: afd_mode_t
  contains
    procedure :: check_settings
    procedure(check_amplitudes_i), deferred :: check_amplitudes
    procedure :: jobs_text => afd_jobs_text
    procedure :: job_label
    procedure :: frequency_hz
    procedure :: run_config => afd_run_config
    procedure :: cost
    procedure :: file_items => afd_file_items
  end type afd_mode_t

  abstract interface
    !> Check `amplitudes_m` (its `n_amp` entries set) and the mode's other variables;
    !> `n_amp` becomes the amplitudes per frequency of a job layout.
    subroutine check_amplitudes_i(this, group, path, n_amp, status)
      import :: afd_mode_t, sweep_group_t, status_t
      class(afd_mode_t), intent(inout) :: this
      type(sweep_group_t), intent(in) :: group
      character(len=*), intent(in) :: path
      integer, intent(inout) :: n_amp
      type(status_t), intent(inout) :: status
    end subroutine check_amplitudes_i
  end interface

contains

  !> The record variables refused, the afd waveform, the frequencies (at least one, each
  !> resolved by at least 20 steps per cycle), then the amplitudes of the mode.
  subroutine check_settings(this, group, base, path, plan, status)
    class(afd_mode_t), intent(inout) :: this
    type(sweep_group_t), intent(in) :: group
    type(config_t), intent(in) :: base
    character(len=*), intent(in) :: path
    type(sweep_plan_t), intent(inout) :: plan
    type(status_t), intent(inout) :: status
    integer :: n_freq, n_amp, k
    real(dp) :: f_max_hz, f_hz

    if (len_trim(group%model_samples_file) > 0) then
      call fail(status, path//": &sweep model_samples_file gives the model samples of an IDA (mode = 'ida'); "// &
                "mode = '"//trim(this%name)//"' takes its parameter sets from the lists (friction_list, ...)")
      return
    end if
    if (any(group%ranges /= unset_real) .or. group%n_samples /= 0 .or. len_trim(group%record_files(1)) > 0 .or. &
        group%dt_check_rows /= 0 .or. group%n_levels > 0) then
      call fail(status, path//": &sweep record_files, scale_tol, scale_max, n_samples, the sampling ranges "// &
                "and dt_check_rows belong to mode = 'ida', msa_levels_g to mode = 'msa', not '"//trim(this%name)//"'")
      return
    end if
    if (base%motion%waveform /= waveform_afd) then
      call fail(status, path//": &motion waveform = '"//trim(base%motion%waveform)// &
                "': a sweep sets the frequency and amplitude of the '"//waveform_afd//"' waveform; use waveform = '"// &
                waveform_afd//"'")
      return
    end if
    n_freq = group%n_frequencies
    if (n_freq == 0) then
      call fail(status, path//': &sweep frequencies_hz is not set: give at least one frequency')
      return
    end if
    f_max_hz = 1.0_dp/(20.0_dp*base%solver%dt_s)
    do k = 1, n_freq
      f_hz = group%frequencies_hz(k)
      call need(f_hz > 0.0_dp .and. f_hz <= f_max_hz, path, 'sweep', 'frequencies_hz('//itoa(k)//')', f_hz, &
                '0 < frequencies_hz <= 1/(20 dt_s) = '//fmt_real(f_max_hz), status)
    end do
    n_amp = group%n_amplitudes
    call this%check_amplitudes(group, path, n_amp, status)
    plan%frequencies_hz = group%frequencies_hz(1:n_freq)
    plan%n_freq = n_freq
    plan%n_freq_per_set = merge(1, n_freq, plan%pair_frequencies)
    plan%n_amp = n_amp
    plan%search = group%search
  end subroutine check_settings

  !> "<sets> parameter sets x <n> frequencies" (or each at its frequency).
  function afd_jobs_text(this, plan) result(text)
    class(afd_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    character(len=:), allocatable :: text
    if (plan%pair_frequencies) then
      text = itoa(plan%n_sets)//' parameter sets, each at its frequency'
    else
      text = itoa(plan%n_sets)//' parameter sets x '//itoa(plan%n_freq)//' frequencies'
    end if
  end function afd_jobs_text

  !> "<frequency> Hz".
  function job_label(this, plan, job) result(text)
    class(afd_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    character(len=:), allocatable :: text
    text = fmt_real(this%frequency_hz(plan, job))//' Hz'
  end function job_label

  !> The frequency of job `job` [Hz]: its set's with pair_frequencies, else the job's
  !> place in the frequency list (amplitudes vary fastest).
  pure real(dp) function frequency_hz(this, plan, job)
    class(afd_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    if (plan%pair_frequencies) then
      frequency_hz = plan%frequencies_hz(job_param_set(plan, job) + 1)
    else
      frequency_hz = plan%frequencies_hz(modulo(job/plan%n_amp, plan%n_freq) + 1)
    end if
  end function frequency_hz

  !> The set's case at the job's frequency and the amplitude `value` [m], stopping at the
  !> collapse and keeping no time series.
  pure function afd_run_config(this, plan, job, value) result(cfg)
    class(afd_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    real(dp), intent(in) :: value
    type(config_t) :: cfg
    cfg = search_run_config(plan%set_cfg(job_param_set(plan, job)), this%frequency_hz(plan, job), value)
  end function afd_run_config

  !> Relative cost of one run of job `job`: steps x bodies.
  pure real(dp) function cost(this, plan, job)
    class(afd_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    real(dp) :: duration_s
    associate (c => plan%set_cfg(job_param_set(plan, job)))
      duration_s = c%motion%duration_s
      if (duration_s == 0.0_dp) duration_s = (c%motion%n_attack + c%motion%n_full + c%motion%n_decay)/ &
                                             this%frequency_hz(plan, job) + c%motion%lead_s + c%motion%rest_s
      cost = duration_s/c%solver%dt_s*run_bodies(c)
    end associate
  end function cost

  !> /sweep/frequencies_hz.
  subroutine afd_file_items(this, plan, datasets, attributes)
    class(afd_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    type(named_values_t), allocatable, intent(out) :: datasets(:)
    type(named_text_t), allocatable, intent(out) :: attributes(:)
    allocate (datasets(1), attributes(0))
    datasets(1)%name = 'frequencies_hz'
    datasets(1)%values = plan%frequencies_hz
  end subroutine afd_file_items

end module voussoir_sweep_mode_afd
