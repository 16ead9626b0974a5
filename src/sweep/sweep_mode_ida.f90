!> Mode `ida` (incremental dynamic analysis, docs/earthquakes.md): a job is a model
!> sample (or parameter set) x a record, records varying fastest, and its search is the
!> threshold search over the record's scale, from the scale at which the record's PGA
!> equals the arch's static capacity. The records, the samples and a run are shared with
!> mode msa (src/sweep/sweep_mode_records.f90); after the searches, an optional check
!> redoes some runs at half the time step.
module voussoir_sweep_mode_ida
  use voussoir_kinds, only: dp, g_m_s2
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa, fmt_real, fmt_exact, fmt_exact_list, join_words
  use voussoir_config, only: config_t
  use voussoir_input_range, only: need_range
  use voussoir_assembly, only: assembly_t
  use voussoir_model, only: model_t
  use voussoir_simulation, only: run_result_t
  use voussoir_setup, only: simulate => run_config
  use voussoir_threshold_search, only: threshold_search_t, threshold_result_t, run_outcome_t, threshold_init_onset
  use voussoir_sweep_group, only: sweep_group_t
  use voussoir_sweep_table, only: sweep_table_t, name_len, table_init, table_row, table_set, table_append, &
                                  table_value
  use voussoir_sweep_mode, only: sweep_plan_t, job_param_set
  use voussoir_sweep_ida, only: record_label
  use voussoir_sweep_mode_records, only: record_mode_t, job_record, check_records_and_samples, records_settings_text, &
                                        record_csv_cells, record_site_cells, record_site_columns
  implicit none
  private

  public :: ida_mode_t, scale_warned, scale_warn_low, scale_warn_high

  !> A threshold scale beyond these is warned of: a record scaled this far from its own
  !> intensity stands for another earthquake than the one recorded.
  real(dp), parameter :: scale_warn_low = 0.25_dp, scale_warn_high = 4.0_dp

  !> The collapse threshold scale of each record, per model sample.
  type, extends(record_mode_t) :: ida_mode_t
    integer :: dt_check_rows = 0                  !! rows whose two bracketing runs are redone at dt/2
  contains
    procedure :: check_settings
    procedure :: settings_text
    procedure :: jobs_text
    procedure :: has_search
    procedure :: search_init
    procedure :: value_name
    procedure :: results_table
    procedure :: result_row
    procedure :: csv_header
    procedure :: csv_line
    procedure :: summary_line
    procedure :: closing_check
    procedure :: row_runs
  end type ida_mode_t

contains

  !> The records and the sampling (the shared check), the scale search.
  subroutine check_settings(this, group, base, path, plan, status)
    class(ida_mode_t), intent(inout) :: this
    type(sweep_group_t), intent(in) :: group
    type(config_t), intent(in) :: base
    character(len=*), intent(in) :: path
    type(sweep_plan_t), intent(inout) :: plan
    type(status_t), intent(inout) :: status

    if (group%n_levels > 0) then
      call fail(status, path//": &sweep msa_levels_g is set but mode = 'ida' searches the scale of each record: "// &
                "remove it, or use mode = 'msa'")
      return
    end if
    call need_range('0 < scale_tol < 1 (relative width of the final bracket)', path, 'sweep', 'scale_tol', &
                    group%scale_tol, status)
    call need_range('scale_max > 0 (finite)', path, 'sweep', 'scale_max', group%scale_max, status)
    call need_range('dt_check_rows >= 0', path, 'sweep', 'dt_check_rows', group%dt_check_rows, status)
    if (.not. status%ok) return
    call check_records_and_samples(this, group, base, path, plan, status)
    if (.not. status%ok) return
    this%dt_check_rows = group%dt_check_rows
    plan%n_amp = 1
    plan%search = group%search
    plan%search%amp_tol_m = group%scale_tol
    plan%search%amp_max_m = group%scale_max
    plan%search%relative_tol = .true.
  end subroutine check_settings

  !> The records, the scale search, the sampling.
  function settings_text(this, plan) result(text)
    class(ida_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    character(len=:), allocatable :: text
    character(len=*), parameter :: nl = achar(10)
    text = records_settings_text(this, plan, '  scale_tol = '//fmt_exact_list([plan%search%amp_tol_m])//nl// &
                                 '  scale_max = '//fmt_exact_list([plan%search%amp_max_m])//nl// &
                                 '  scan_step = '//fmt_exact_list([plan%search%scan_step])//nl// &
                                 '  refine_factor = '//itoa(plan%search%refine_factor)//nl// &
                                 '  n_confirm = '//itoa(plan%search%n_confirm)//nl, &
                                 '  dt_check_rows = '//itoa(this%dt_check_rows)//nl)
  end function settings_text

  function jobs_text(this, plan) result(text)
    class(ida_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    character(len=:), allocatable :: text
    text = itoa(plan%n_sets)//' model samples x '//itoa(plan%records%n)//' records'
  end function jobs_text

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
      call threshold_init_onset(search, c, this%capacity_m_s2(job_param_set(plan, job))/ &
                                plan%records%pga_m_s2(job_record(plan, job)), &
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
                        'distance_km', 'pga_m_s2', 'static_capacity_m_s2', record_site_columns], &
                    [.true., .true., .true., .false., .false., .false., .false., .true., .true., .true., &
                     .false., .false., .true., .false., .false., .false., .false., .false., .false., .false.])
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
    call this%set_record_columns(plan, job, results, row)
  end subroutine result_row

  function csv_header(this, names) result(text)
    class(ida_mode_t), intent(in) :: this
    character(len=*), intent(in) :: names
    character(len=:), allocatable :: text
    text = 'record,param_set'//names//',scale_stood,scale_threshold,pga_threshold_m_s2,pgv_threshold_m_s,'// &
           'censored,non_monotonic,n_runs,failed,event,magnitude,distance_km,pga_m_s2,static_capacity_m_s2,'// &
           join_words(record_site_columns, ',')
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
           record_csv_cells(plan, rec)//','// &
           fmt_exact(table_value(results, 'static_capacity_m_s2', r))//record_site_cells(plan, rec)
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

  !> The runs that bracket row `r`'s threshold: at scale_stood ('stood', where above 0 and
  !> below the threshold) and at scale_threshold ('collapsed'); a censored row's at
  !> scale_max ('stood'); a failed row's last stand, where known.
  subroutine row_runs(this, plan, results, r, values, words)
    class(ida_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_table_t), intent(in) :: results
    integer, intent(in) :: r
    real(dp), allocatable, intent(out) :: values(:)
    character(len=16), allocatable, intent(out) :: words(:)
    real(dp) :: stood, threshold
    stood = table_value(results, 'scale_stood', r)
    threshold = table_value(results, 'scale_threshold', r)
    allocate (values(0), words(0))
    if (stood > 0.0_dp .and. (stood < threshold .or. nint(table_value(results, 'censored', r)) == 1 .or. &
                              nint(table_value(results, 'failed', r)) == 1)) then
      values = [stood]
      words = [character(len=16) :: 'stood']
    end if
    if (nint(table_value(results, 'censored', r)) == 1 .or. nint(table_value(results, 'failed', r)) == 1) return
    values = [values, threshold]
    words = [character(len=16) :: words, 'collapsed']
  end subroutine row_runs

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
