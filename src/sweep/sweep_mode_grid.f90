!> Mode `grid`: every frequency x amplitude of the lists, each job one run that keeps
!> the base case's stop_after_collapse_s (so that a row is what voussoir-run gives).
module voussoir_sweep_mode_grid
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa, fmt_exact, fmt_exact_list
  use voussoir_config, only: config_t
  use voussoir_threshold_search, only: threshold_result_t, run_outcome_t
  use voussoir_input_range, only: need_range
  use voussoir_sweep_group, only: sweep_group_t
  use voussoir_sweep_table, only: sweep_table_t, named_values_t, named_text_t, name_len, table_init, table_set, &
                                  table_value
  use voussoir_sweep_mode, only: sweep_plan_t, job_param_set
  use voussoir_sweep_mode_afd, only: afd_mode_t, afd_jobs_text, afd_run_config, afd_file_items
  implicit none
  private

  public :: grid_mode_t

  !> Stand or collapse at every frequency x amplitude.
  type, extends(afd_mode_t) :: grid_mode_t
    real(dp), allocatable :: amplitudes_m(:)   !! the commanded amplitudes [m]
  contains
    procedure :: check_amplitudes
    procedure :: settings_text
    procedure :: jobs_text
    procedure :: run_value
    procedure :: run_config
    procedure :: results_table
    procedure :: result_row
    procedure :: file_items
    procedure :: csv_header
    procedure :: csv_line
    procedure :: summary_line
  end type grid_mode_t

contains

  !> At least one amplitude, each >= 0 and finite.
  subroutine check_amplitudes(this, group, path, n_amp, status)
    class(grid_mode_t), intent(inout) :: this
    type(sweep_group_t), intent(in) :: group
    character(len=*), intent(in) :: path
    integer, intent(inout) :: n_amp
    type(status_t), intent(inout) :: status
    integer :: k
    if (n_amp == 0) then
      call fail(status, path//": &sweep amplitudes_m is not set: mode = 'grid' needs at least one amplitude")
      return
    end if
    do k = 1, n_amp
      call need_range('0 <= amplitudes_m (finite)', path, 'sweep', 'amplitudes_m('//itoa(k)//')', group%amplitudes_m(k), &
                      status)
    end do
    this%amplitudes_m = group%amplitudes_m(1:n_amp)
  end subroutine check_amplitudes

  !> The frequencies and the amplitudes.
  function settings_text(this, plan) result(text)
    class(grid_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    character(len=:), allocatable :: text
    text = '  frequencies_hz = '//fmt_exact_list(plan%frequencies_hz)//achar(10)// &
           '  amplitudes_m = '//fmt_exact_list(this%amplitudes_m)//achar(10)
  end function settings_text

  !> The sets and frequencies, x the amplitudes.
  function jobs_text(this, plan) result(text)
    class(grid_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    character(len=:), allocatable :: text
    text = afd_jobs_text(this, plan)//' x '//itoa(plan%n_amp)//' amplitudes'
  end function jobs_text

  !> The amplitude of job `job` [m] (amplitudes vary fastest).
  pure real(dp) function run_value(this, plan, job)
    class(grid_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    run_value = this%amplitudes_m(modulo(job, plan%n_amp) + 1)
  end function run_value

  !> An afd run that keeps the base case's stop_after_collapse_s.
  pure function run_config(this, plan, job, value) result(cfg)
    class(grid_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    real(dp), intent(in) :: value
    type(config_t) :: cfg
    cfg = afd_run_config(this, plan, job, value)
    cfg%output%stop_after_collapse_s = plan%set_cfg(job_param_set(plan, job))%output%stop_after_collapse_s
  end function run_config

  function results_table(this) result(t)
    class(grid_mode_t), intent(in) :: this
    type(sweep_table_t) :: t
    call table_init(t, [character(len=name_len) :: 'job', 'param_set', 'frequency_hz', 'amplitude_m', &
                        'collapsed', 'collapse_time_s', 'peak_crown_disp_m', 'mean_iterations', &
                        'nonconverged_steps', 'wall_time_s', 'failed'], &
                    [.true., .true., .false., .false., .true., .false., .false., .false., .true., .false., .true.])
  end function results_table

  !> The row of the job's one run.
  subroutine result_row(this, plan, job, o, r, failed, results, row)
    class(grid_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    type(run_outcome_t), intent(in) :: o
    type(threshold_result_t), intent(in) :: r
    logical, intent(in) :: failed
    type(sweep_table_t), intent(in) :: results
    real(dp), intent(inout) :: row(:)
    call table_set(results, row, 'job', real(job, dp))
    call table_set(results, row, 'param_set', real(job_param_set(plan, job), dp))
    call table_set(results, row, 'frequency_hz', this%frequency_hz(plan, job))
    call table_set(results, row, 'amplitude_m', o%amplitude_m)
    call table_set(results, row, 'collapsed', merge(1.0_dp, 0.0_dp, o%collapsed))
    call table_set(results, row, 'collapse_time_s', o%collapse_time_s)
    call table_set(results, row, 'peak_crown_disp_m', o%peak_crown_disp_m)
    call table_set(results, row, 'mean_iterations', o%mean_iterations)
    call table_set(results, row, 'nonconverged_steps', real(o%nonconverged_steps, dp))
    call table_set(results, row, 'wall_time_s', o%wall_time_s)
  end subroutine result_row

  !> /sweep/frequencies_hz and /sweep/amplitudes_m.
  subroutine file_items(this, plan, datasets, attributes)
    class(grid_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    type(named_values_t), allocatable, intent(out) :: datasets(:)
    type(named_text_t), allocatable, intent(out) :: attributes(:)
    call afd_file_items(this, plan, datasets, attributes)
    datasets = [datasets, named_values_t('amplitudes_m', this%amplitudes_m)]
  end subroutine file_items

  function csv_header(this, names) result(text)
    class(grid_mode_t), intent(in) :: this
    character(len=*), intent(in) :: names
    character(len=:), allocatable :: text
    text = 'param_set'//names//',frequency_hz,amplitude_m,outcome,collapse_time_s,peak_crown_disp_m,mean_iterations'
  end function csv_header

  !> A run's outcome in words: collapse, stand, or failed (the run stopped with an error).
  function csv_line(this, plan, results, r, set_columns) result(line)
    class(grid_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_table_t), intent(in) :: results
    integer, intent(in) :: r
    character(len=*), intent(in) :: set_columns
    character(len=:), allocatable :: line, word
    if (nint(table_value(results, 'failed', r)) == 1) then
      word = 'failed'
    else if (nint(table_value(results, 'collapsed', r)) == 1) then
      word = 'collapse'
    else
      word = 'stand'
    end if
    line = set_columns//','//fmt_exact(table_value(results, 'frequency_hz', r))//','// &
           fmt_exact(table_value(results, 'amplitude_m', r))//','//word//','// &
           fmt_exact(table_value(results, 'collapse_time_s', r))//','// &
           fmt_exact(table_value(results, 'peak_crown_disp_m', r))//','// &
           fmt_exact(table_value(results, 'mean_iterations', r))
  end function csv_line

  !> None: a grid is read from its file.
  function summary_line(this, plan, results, r) result(line)
    class(grid_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_table_t), intent(in) :: results
    integer, intent(in) :: r
    character(len=:), allocatable :: line
    line = ''
  end function summary_line

end module voussoir_sweep_mode_grid
