!> Mode `msa` (multiple-stripe analysis, docs/earthquakes.md): each record scaled so that
!> its PGA equals each of the stated levels `msa_levels_g` [g], one run per model sample
!> x record x level (levels varying fastest, then records), its outcome collapsed or
!> not. No search: a record that brings the arch down at one level and not at a higher
!> one is two rows as they came, and the fragility is fitted to the fraction collapsed
!> at each level (Baker 2015). Each row also keeps the run's largest joint opening and
!> the crown's residual drift (mm), so that the fragilities of hinge onset and of a
!> residual drift come from the same stripes. The records, the samples and a run are
!> shared with mode ida (src/sweep/sweep_mode_records.f90).
module voussoir_sweep_mode_msa
  use voussoir_kinds, only: dp, g_m_s2
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa, fmt_real, fmt_exact, fmt_exact_list, join_words
  use voussoir_config, only: config_t
  use voussoir_input_range, only: need_range
  use voussoir_threshold_search, only: threshold_result_t, run_outcome_t
  use voussoir_sweep_group, only: sweep_group_t, unset_real
  use voussoir_sweep_table, only: sweep_table_t, named_values_t, named_text_t, name_len, table_init, table_set, &
                                  table_value
  use voussoir_sweep_mode, only: sweep_plan_t, job_param_set
  use voussoir_sweep_ida, only: record_label
  use voussoir_sweep_mode_records, only: record_mode_t, job_record, check_records_and_samples, records_settings_text, &
                                         records_file_items, record_csv_cells, record_site_cells, &
                                         record_site_columns
  use voussoir_sweep_mode_ida, only: scale_warn_low, scale_warn_high
  implicit none
  private

  public :: msa_mode_t, job_level

  !> Stand or collapse of every record at every level, per model sample.
  type, extends(record_mode_t) :: msa_mode_t
    real(dp), allocatable :: levels_g(:)   !! the PGA each record is scaled to [g], increasing
  contains
    procedure :: check_settings
    procedure :: settings_text
    procedure :: jobs_text
    procedure :: run_value
    procedure :: value_name
    procedure :: results_table
    procedure :: result_row
    procedure :: file_items
    procedure :: csv_header
    procedure :: csv_line
    procedure :: summary_line
    procedure :: closing_check
    procedure :: bridge_refusal
  end type msa_mode_t

contains

  !> Its rows keep the hinge onset by the arch's joints, which a bridge does not number.
  function bridge_refusal(this) result(why)
    class(msa_mode_t), intent(in) :: this
    character(len=:), allocatable :: why
    why = "its rows keep the largest opening of an arch's numbered joints (max_joint_opening_mm), and a "// &
          "bridge's joints are not numbered"
  end function bridge_refusal

  !> Level (1-based, into levels_g) of job `job`.
  pure integer function job_level(plan, job)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    job_level = modulo(job, plan%n_amp) + 1
  end function job_level

  !> The levels (at least one, each > 0 and finite, strictly increasing), then the
  !> records and the sampling (the shared check); the variables of the IDA's search
  !> refused.
  subroutine check_settings(this, group, base, path, plan, status)
    class(msa_mode_t), intent(inout) :: this
    type(sweep_group_t), intent(in) :: group
    type(config_t), intent(in) :: base
    character(len=*), intent(in) :: path
    type(sweep_plan_t), intent(inout) :: plan
    type(status_t), intent(inout) :: status
    integer :: k, n

    n = group%n_levels
    if (n == 0) then
      call fail(status, path//": &sweep msa_levels_g is not set: mode = 'msa' needs at least one intensity "// &
                "level (the PGA in g each record is scaled to, e.g. msa_levels_g = 0.2, 0.3, 0.4)")
      return
    end if
    if (group%dt_check_rows /= 0) then
      call fail(status, path//': &sweep dt_check_rows = '//itoa(group%dt_check_rows)//" belongs to mode = 'ida' "// &
                "(it redoes the runs bracketing a threshold), not 'msa'")
      return
    end if
    do k = 1, n
      call need_range('0 < msa_levels_g <= 100 g (finite)', path, 'sweep', 'msa_levels_g('//itoa(k)//')', &
                      group%msa_levels_g(k), status)
      if (.not. status%ok) return
      if (k > 1) then
        if (.not. group%msa_levels_g(k) > group%msa_levels_g(k - 1)) then
          call fail(status, path//': &sweep msa_levels_g('//itoa(k)//') = '//fmt_real(group%msa_levels_g(k))// &
                    ' g is not above msa_levels_g('//itoa(k - 1)//') = '//fmt_real(group%msa_levels_g(k - 1))// &
                    ' g: the levels must be strictly increasing')
          return
        end if
      end if
    end do
    call check_records_and_samples(this, group, base, path, plan, status)
    if (.not. status%ok) return
    this%levels_g = group%msa_levels_g(1:n)
    plan%n_amp = n
  end subroutine check_settings

  !> The records, the levels, the sampling.
  function settings_text(this, plan) result(text)
    class(msa_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    character(len=:), allocatable :: text
    text = records_settings_text(this, plan, '  msa_levels_g = '//fmt_exact_list(this%levels_g)//achar(10), '')
  end function settings_text

  !> The jobs in words, and before any run how many scale their record beyond
  !> scale_warn_high or below scale_warn_low (the scales are known from the plan).
  function jobs_text(this, plan) result(text)
    class(msa_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    character(len=:), allocatable :: text
    integer :: job, n_warned
    real(dp) :: scale
    text = itoa(plan%n_sets)//' model samples x '//itoa(plan%records%n)//' records x '//itoa(plan%n_amp)//' levels'
    n_warned = 0
    do job = 0, plan%n_jobs - 1
      scale = this%run_value(plan, job)
      if (scale > scale_warn_high .or. scale < scale_warn_low) n_warned = n_warned + 1
    end do
    if (n_warned > 0) text = text//'; warning: '//itoa(n_warned)//' runs scale their record beyond '// &
                             fmt_real(scale_warn_high)//' or below '//fmt_real(scale_warn_low)
  end function jobs_text

  !> The scale of job `job`'s record that makes its PGA the job's level.
  pure real(dp) function run_value(this, plan, job)
    class(msa_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    run_value = this%levels_g(job_level(plan, job))*g_m_s2/plan%records%pga_m_s2(job_record(plan, job))
  end function run_value

  pure function value_name(this) result(name)
    class(msa_mode_t), intent(in) :: this
    character(len=:), allocatable :: name
    name = 'scale'
  end function value_name

  function results_table(this) result(t)
    class(msa_mode_t), intent(in) :: this
    type(sweep_table_t) :: t
    call table_init(t, [character(len=name_len) :: 'job', 'param_set', 'record', 'level_g', 'scale', 'collapsed', &
                        'collapse_time_s', 'peak_crown_disp_m', 'mean_iterations', 'nonconverged_steps', &
                        'wall_time_s', 'failed', 'magnitude', 'distance_km', 'pga_m_s2', 'static_capacity_m_s2', &
                        'max_joint_opening_mm', 'residual_drift_mm', record_site_columns], &
                    [.true., .true., .true., .false., .false., .true., .false., .false., .false., .true., &
                     .false., .true., .false., .false., .false., .false., .false., .false., .false., .false., .false.])
  end function results_table

  !> The row of the job's one run.
  subroutine result_row(this, plan, job, o, r, failed, results, row)
    class(msa_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    type(run_outcome_t), intent(in) :: o
    type(threshold_result_t), intent(in) :: r
    logical, intent(in) :: failed
    type(sweep_table_t), intent(in) :: results
    real(dp), intent(inout) :: row(:)
    integer :: rec
    rec = job_record(plan, job)
    call table_set(results, row, 'job', real(job, dp))
    call table_set(results, row, 'param_set', real(job_param_set(plan, job), dp))
    call table_set(results, row, 'record', real(rec - 1, dp))
    call table_set(results, row, 'level_g', this%levels_g(job_level(plan, job)))
    call table_set(results, row, 'scale', o%amplitude_m)
    call table_set(results, row, 'collapsed', merge(1.0_dp, 0.0_dp, o%collapsed .and. .not. failed))
    call table_set(results, row, 'collapse_time_s', o%collapse_time_s)
    call table_set(results, row, 'peak_crown_disp_m', o%peak_crown_disp_m)
    call table_set(results, row, 'mean_iterations', o%mean_iterations)
    call table_set(results, row, 'nonconverged_steps', real(o%nonconverged_steps, dp))
    call table_set(results, row, 'wall_time_s', o%wall_time_s)
    call this%set_record_columns(plan, job, results, row)
    ! The limit states short of collapse, in mm: hinge onset (an opening above about 1 mm)
    ! and a residual drift come from the same stripes.
    call table_set(results, row, 'max_joint_opening_mm', 1.0e3_dp*o%peak_joint_opening_m)
    call table_set(results, row, 'residual_drift_mm', 1.0e3_dp*o%residual_crown_drift_m)
  end subroutine result_row

  !> The records' items (the shared ones) and /sweep/msa_levels_g.
  subroutine file_items(this, plan, datasets, attributes)
    class(msa_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    type(named_values_t), allocatable, intent(out) :: datasets(:)
    type(named_text_t), allocatable, intent(out) :: attributes(:)
    call records_file_items(this, plan, datasets, attributes)
    datasets = [datasets, named_values_t('msa_levels_g', this%levels_g)]
  end subroutine file_items

  function csv_header(this, names) result(text)
    class(msa_mode_t), intent(in) :: this
    character(len=*), intent(in) :: names
    character(len=:), allocatable :: text
    text = 'record,param_set'//names//',level_g,scale,collapsed,failed,event,magnitude,distance_km,pga_m_s2,'// &
           'collapse_time_s,peak_crown_disp_m,mean_iterations,static_capacity_m_s2,max_joint_opening_mm,'// &
           'residual_drift_mm,'//join_words(record_site_columns, ',')
  end function csv_header

  function csv_line(this, plan, results, r, set_columns) result(line)
    class(msa_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_table_t), intent(in) :: results
    integer, intent(in) :: r
    character(len=*), intent(in) :: set_columns
    character(len=:), allocatable :: line
    integer :: rec
    rec = nint(table_value(results, 'record', r)) + 1
    line = record_label(plan%records, rec)//','//set_columns//','// &
           fmt_exact(table_value(results, 'level_g', r))//','//fmt_exact(table_value(results, 'scale', r))//','// &
           itoa(nint(table_value(results, 'collapsed', r)))//','//itoa(nint(table_value(results, 'failed', r)))// &
           record_csv_cells(plan, rec)//','// &
           fmt_exact(table_value(results, 'collapse_time_s', r))//','// &
           fmt_exact(table_value(results, 'peak_crown_disp_m', r))//','// &
           fmt_exact(table_value(results, 'mean_iterations', r))//','// &
           fmt_exact(table_value(results, 'static_capacity_m_s2', r))//','// &
           fmt_exact(table_value(results, 'max_joint_opening_mm', r))//','// &
           fmt_exact(table_value(results, 'residual_drift_mm', r))//record_site_cells(plan, rec)
  end function csv_line

  !> None per row: the stripes are summed up after the runs (closing_check).
  function summary_line(this, plan, results, r) result(line)
    class(msa_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_table_t), intent(in) :: results
    integer, intent(in) :: r
    character(len=:), allocatable :: line
    line = ''
  end function summary_line

  !> The stripes in a line ("stripes (collapsed / runs): 0.2 g 0/4, 0.3 g 1/4, ..."; the
  !> runs that failed counted apart), and a warning when some runs scaled their record
  !> beyond scale_warn_high or below scale_warn_low. No extra table.
  subroutine closing_check(this, plan, results, extra, report, status)
    class(msa_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_table_t), intent(in) :: results
    type(sweep_table_t), intent(out) :: extra
    character(len=:), allocatable, intent(out) :: report
    type(status_t), intent(inout) :: status
    integer :: k, r, n_runs, n_collapsed, n_failed, n_warned
    real(dp) :: scale
    report = 'stripes (collapsed / runs):'
    n_warned = 0
    do k = 1, size(this%levels_g)
      n_runs = 0
      n_collapsed = 0
      n_failed = 0
      do r = 1, results%n_rows
        if (job_level(plan, nint(table_value(results, 'job', r))) /= k) cycle
        if (nint(table_value(results, 'failed', r)) == 1) then
          n_failed = n_failed + 1
          cycle
        end if
        n_runs = n_runs + 1
        if (nint(table_value(results, 'collapsed', r)) == 1) n_collapsed = n_collapsed + 1
      end do
      report = report//' '//fmt_real(this%levels_g(k))//' g '//itoa(n_collapsed)//'/'//itoa(n_runs)
      if (n_failed > 0) report = report//' ('//itoa(n_failed)//' failed)'
      if (k < size(this%levels_g)) report = report//','
    end do
    do r = 1, results%n_rows
      scale = table_value(results, 'scale', r)
      if (scale > scale_warn_high .or. scale < scale_warn_low) n_warned = n_warned + 1
    end do
    if (n_warned > 0) report = report//'; warning: '//itoa(n_warned)//' of '//itoa(results%n_rows)// &
      ' runs scaled their record beyond '//fmt_real(scale_warn_high)//' or below '//fmt_real(scale_warn_low)// &
      ' (the record then stands for another earthquake than the one recorded; column scale)'
  end subroutine closing_check

end module voussoir_sweep_mode_msa
