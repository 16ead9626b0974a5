!> Mode `threshold`: per parameter set and frequency, the smallest afd amplitude that
!> collapses the arch, found by the threshold search (src/sweep/threshold_search.f90)
!> from the static onset; the columns of docs/results_format.md.
module voussoir_sweep_mode_threshold
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa, fmt_real, fmt_exact, fmt_exact_list
  use voussoir_threshold_search, only: threshold_search_t, threshold_result_t, run_outcome_t
  use voussoir_threshold, only: threshold_init, afd_peak_accel_per_m
  use voussoir_input_range, only: need, need_range
  use voussoir_sweep_group, only: sweep_group_t
  use voussoir_sweep_table, only: sweep_table_t, name_len, table_init, table_set, table_value
  use voussoir_sweep_mode, only: sweep_plan_t, job_param_set
  use voussoir_sweep_mode_afd, only: afd_mode_t
  implicit none
  private

  public :: threshold_mode_t

  !> The collapse threshold amplitude at each frequency.
  type, extends(afd_mode_t) :: threshold_mode_t
  contains
    procedure :: check_amplitudes
    procedure :: settings_text
    procedure :: has_search
    procedure :: search_init
    procedure :: results_table
    procedure :: result_row
    procedure :: csv_header
    procedure :: csv_line
    procedure :: summary_line
    procedure :: row_runs
  end type threshold_mode_t

contains

  !> No amplitudes (the search finds them); the search settings in range.
  subroutine check_amplitudes(this, group, path, n_amp, status)
    class(threshold_mode_t), intent(inout) :: this
    type(sweep_group_t), intent(in) :: group
    character(len=*), intent(in) :: path
    integer, intent(inout) :: n_amp
    type(status_t), intent(inout) :: status
    if (n_amp > 0) then
      call fail(status, path//": &sweep amplitudes_m is set but mode = 'threshold' searches the "// &
                "amplitude: remove amplitudes_m or use mode = 'grid'")
      return
    end if
    n_amp = 1
    associate (s => group%search)
      ! A search ends: at most about 60 halvings from amp_max_m down to amp_tol_m.
      call need_range('1e-7 m (0.1 micrometre) <= amp_tol_m (finite)', path, 'sweep', 'amp_tol_m', s%amp_tol_m, status)
      call need(s%amp_max_m > s%amp_tol_m .and. s%amp_max_m <= 1.0e3_dp, path, 'sweep', 'amp_max_m', s%amp_max_m, &
                'amp_tol_m = '//fmt_real(s%amp_tol_m)//' < amp_max_m <= 1000 m', status)
      call need_range('0 < scan_step <= 1', path, 'sweep', 'scan_step', s%scan_step, status)
      call need_range('2 <= refine_factor <= 64 (2: bisection)', path, 'sweep', 'refine_factor', s%refine_factor, status)
      call need_range('0 <= n_confirm <= 16', path, 'sweep', 'n_confirm', s%n_confirm, status)
    end associate
  end subroutine check_amplitudes

  !> The frequencies and the search settings.
  function settings_text(this, plan) result(text)
    class(threshold_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    character(len=:), allocatable :: text
    character(len=*), parameter :: nl = achar(10)
    text = '  frequencies_hz = '//fmt_exact_list(plan%frequencies_hz)//nl// &
           '  amp_tol_m = '//fmt_exact_list([plan%search%amp_tol_m])//nl// &
           '  amp_max_m = '//fmt_exact_list([plan%search%amp_max_m])//nl// &
           '  scan_step = '//fmt_exact_list([plan%search%scan_step])//nl// &
           '  refine_factor = '//itoa(plan%search%refine_factor)//nl// &
           '  n_confirm = '//itoa(plan%search%n_confirm)//nl
  end function settings_text

  pure logical function has_search(this)
    class(threshold_mode_t), intent(in) :: this
    has_search = .true.
  end function has_search

  !> A search from the static onset of the job's set at its frequency.
  subroutine search_init(this, plan, job, search, status)
    class(threshold_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    type(threshold_search_t), intent(out) :: search
    type(status_t), intent(inout) :: status
    call threshold_init(search, plan%set_cfg(job_param_set(plan, job)), this%frequency_hz(plan, job), plan%search, &
                        status)
  end subroutine search_init

  function results_table(this) result(t)
    class(threshold_mode_t), intent(in) :: this
    type(sweep_table_t) :: t
    call table_init(t, [character(len=name_len) :: 'job', 'param_set', 'frequency_hz', 'threshold_m', &
                        'peak_accel_m_s2', 'full_cycle_accel_m_s2', 'non_monotonic', 'n_runs', &
                        'mean_iterations', 'stand_below_m', 'static_onset_m', 'wall_time_s', 'failed'], &
                    [.true., .true., .false., .false., .false., .false., .true., .true., .false., .false., &
                     .false., .false., .true.])
  end function results_table

  !> The row of a finished search. Two accelerations at the threshold: the true peak of
  !> the commanded afd motion (its envelopes add to it: about 1.05 A (2 pi f)^2 for 1-1-1
  !> cycles) and the full-cycle A (2 pi f)^2.
  subroutine result_row(this, plan, job, o, r, failed, results, row)
    class(threshold_mode_t), intent(in) :: this
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
    call table_set(results, row, 'threshold_m', r%threshold_m)
    call table_set(results, row, 'peak_accel_m_s2', r%threshold_m* &
                   afd_peak_accel_per_m(plan%set_cfg(job_param_set(plan, job)), this%frequency_hz(plan, job)))
    call table_set(results, row, 'full_cycle_accel_m_s2', r%full_cycle_accel_m_s2)
    call table_set(results, row, 'non_monotonic', merge(1.0_dp, 0.0_dp, r%non_monotonic))
    call table_set(results, row, 'n_runs', real(r%n_runs, dp))
    call table_set(results, row, 'mean_iterations', r%mean_iterations)
    call table_set(results, row, 'stand_below_m', r%stand_below_m)
    call table_set(results, row, 'static_onset_m', r%onset_amp_m)
    call table_set(results, row, 'wall_time_s', r%wall_time_s)
  end subroutine result_row

  function csv_header(this, names) result(text)
    class(threshold_mode_t), intent(in) :: this
    character(len=*), intent(in) :: names
    character(len=:), allocatable :: text
    text = 'param_set'//names//',frequency_hz,threshold_m,peak_accel_m_s2,full_cycle_accel_m_s2,non_monotonic,failed'
  end function csv_header

  function csv_line(this, plan, results, r, set_columns) result(line)
    class(threshold_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_table_t), intent(in) :: results
    integer, intent(in) :: r
    character(len=*), intent(in) :: set_columns
    character(len=:), allocatable :: line
    line = set_columns//','//fmt_exact(table_value(results, 'frequency_hz', r))//','// &
           fmt_exact(table_value(results, 'threshold_m', r))//','// &
           fmt_exact(table_value(results, 'peak_accel_m_s2', r))//','// &
           fmt_exact(table_value(results, 'full_cycle_accel_m_s2', r))//','// &
           itoa(nint(table_value(results, 'non_monotonic', r)))//','//itoa(nint(table_value(results, 'failed', r)))
  end function csv_line

  !> "f = ... Hz: threshold ... mm (peak ... m/s2), n runs" (the true peak of the motion).
  function summary_line(this, plan, results, r) result(line)
    class(threshold_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_table_t), intent(in) :: results
    integer, intent(in) :: r
    character(len=:), allocatable :: line
    character(len=160) :: buf
    real(dp) :: thr, f_hz
    integer :: n_runs
    f_hz = this%frequency_hz(plan, nint(table_value(results, 'job', r)))
    thr = table_value(results, 'threshold_m', r)
    n_runs = nint(table_value(results, 'n_runs', r))
    if (nint(table_value(results, 'failed', r)) == 1) then
      write (buf, '(a,f7.3,a,i3,a)') '  f = ', f_hz, ' Hz: FAILED (a run stopped with an '// &
        'error, see above), ', n_runs, ' runs'
    else if (thr == thr) then
      write (buf, '(a,f7.3,a,f9.3,a,f8.3,a,i3,a)') '  f = ', f_hz, ' Hz: threshold ', 1.0e3_dp*thr, ' mm (peak', &
        table_value(results, 'peak_accel_m_s2', r), ' m/s2), ', n_runs, ' runs'
    else
      write (buf, '(a,f7.3,a,i3,a)') '  f = ', f_hz, ' Hz: stands up to amp_max_m, ', n_runs, ' runs'
    end if
    line = trim(buf)
  end function summary_line

  !> The run at the row's threshold amplitude ('threshold'), where the search found one.
  subroutine row_runs(this, plan, results, r, values, words)
    class(threshold_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_table_t), intent(in) :: results
    integer, intent(in) :: r
    real(dp), allocatable, intent(out) :: values(:)
    character(len=16), allocatable, intent(out) :: words(:)
    real(dp) :: threshold_m
    threshold_m = table_value(results, 'threshold_m', r)
    allocate (values(0), words(0))
    if (.not. threshold_m > 0.0_dp) return
    values = [threshold_m]
    words = [character(len=16) :: 'threshold']
  end subroutine row_runs

end module voussoir_sweep_mode_threshold
