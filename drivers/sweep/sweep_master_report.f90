!> The master's progress lines and its closing table: how a sweep reports while it runs.
submodule (voussoir_sweep_master) voussoir_sweep_master_report
  implicit none

contains

  !> A progress line every `progress_every_s` (0: none) and the last one: jobs and runs
  !> done, elapsed time, and the time left estimated from the cost of the runs still to come.
  module subroutine report(plan, m, n_ranks, final)
    type(sweep_plan_t), intent(in) :: plan
    type(master_t), intent(inout) :: m
    integer, intent(in) :: n_ranks
    logical, intent(in) :: final
    real(dp) :: now_s, elapsed_s, left, runs_per_search, eta_s, runs_left
    integer :: job, r, done_runs
    character(len=:), allocatable :: runs
    character(len=32) :: eta
    now_s = wall_s()
    if (.not. final .and. (plan%progress_every_s == 0.0_dp .or. now_s - m%last_report_s < plan%progress_every_s)) &
      return
    m%last_report_s = now_s
    elapsed_s = now_s - m%t0_s
    if (final) then
      ! Busy: the simulations' share of the ranks' time (the rest is waiting, messages, I/O).
      write (output_unit, '(a)') 'voussoir-sweep: done: '//itoa(plan%n_jobs)//' jobs, '// &
        itoa(m%n_runs)//' runs in '//fmt_fixed(elapsed_s, 2)//' s on '//itoa(n_ranks)//' ranks (busy '// &
        fmt_fixed(100.0_dp*m%busy_s/max(n_ranks*elapsed_s, tiny(1.0_dp)), 1)//' %; '//itoa(m%n_runs_resumed)// &
        ' runs kept from the file); '//m%path//', '//m%csv_path
      if (m%n_failed > 0) write (output_unit, '(a)') 'voussoir-sweep: warning: '//itoa(m%n_failed)// &
        ' jobs ended by a run that failed (column failed = 1 in the results; the reasons are printed above)'
      flush (output_unit)
      return
    end if
    ! Work left, in run costs; a search is expected to take as many runs as the finished ones.
    runs_per_search = first_guess_runs
    if (plan%mode%has_search() .and. m%results%n_rows > 0) then
      runs_per_search = 0.0_dp
      do r = 1, m%results%n_rows
        runs_per_search = runs_per_search + table_value(m%results, 'n_runs', r)/m%results%n_rows
      end do
    end if
    left = 0.0_dp
    runs_left = 0.0_dp
    do job = 0, plan%n_jobs - 1
      if (m%state(job) == job_done) cycle
      if (plan%mode%has_search()) then
        runs_left = runs_left + max(1.0_dp, runs_per_search - m%search(job)%n_runs)
        left = left + m%cost(job)*max(1.0_dp, runs_per_search - m%search(job)%n_runs)
      else
        runs_left = runs_left + 1.0_dp
        left = left + m%cost(job)
      end if
    end do
    eta = '?'
    if (m%cost_done > 0.0_dp) then
      eta_s = elapsed_s*left/m%cost_done
      eta = time_text(eta_s)
    end if
    ! Runs done / total (a threshold search's total is an estimate until it ends).
    done_runs = m%n_runs + m%n_runs_resumed
    if (plan%mode%has_search()) then
      runs = itoa(m%n_done)//'/'//itoa(plan%n_jobs)//' searches, '//itoa(done_runs)//'/~'// &
             itoa(done_runs + nint(runs_left))//' runs'
    else
      runs = itoa(done_runs)//'/'//itoa(plan%n_jobs)//' runs'
    end if
    write (output_unit, '(a)') 'voussoir-sweep: '//runs//', elapsed '//fmt_fixed(elapsed_s, 1)//' s, ETA '//trim(eta)
    flush (output_unit)
  end subroutine report

  !> The plan's cost before it starts (issue 26): jobs, runs, simulated seconds and a
  !> rough wall time at `step_block_s` per step and block on `n_ranks` ranks (rank 0
  !> computes too).
  module subroutine estimate(plan, n_ranks)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: n_ranks
    !> Wall time of one step of one block: what the seed's grid sweeps took (3 to 5 us).
    real(dp), parameter :: step_block_s = 4.0e-6_dp
    character(len=:), allocatable :: about
    about = ''
    if (plan%mode%has_search()) about = 'about '
    write (output_unit, '(a)') 'voussoir-sweep: estimate: '//itoa(plan%n_jobs)//' jobs, '//about// &
      itoa(nint(plan%est_runs))//' runs, '//fmt_significant(plan%est_simulated_s, 3)//' s simulated, roughly '// &
      time_text(plan%est_step_blocks*step_block_s/n_ranks)//' of wall time on '//itoa(n_ranks)// &
      ' ranks (at 4 us per step and block; iterations and early collapses change it several-fold)'
    flush (output_unit)
  end subroutine estimate

  !> A duration in words: seconds, minutes or hours.
  function time_text(seconds) result(text)
    real(dp), intent(in) :: seconds
    character(len=:), allocatable :: text
    if (seconds < 120.0_dp) then
      text = itoa(nint(seconds))//' s'
    else if (seconds < 7200.0_dp) then
      text = itoa(nint(seconds/60.0_dp))//' min'
    else
      text = fmt_fixed(seconds/3600.0_dp, 1)//' h'
    end if
  end function time_text

  !> The results of a short sweep, for the log: a line per row in the words of the mode
  !> (none for a grid), its parameter set beside it.
  module subroutine summary(plan, m)
    type(sweep_plan_t), intent(in) :: plan
    type(master_t), intent(in) :: m
    integer :: r
    character(len=:), allocatable :: line
    if (plan%n_jobs > max_listed_jobs) return
    do r = 1, m%results%n_rows
      line = plan%mode%summary_line(plan, m%results, r)
      if (len(line) == 0) cycle
      if (nint(table_value(m%results, 'non_monotonic', r)) == 1) line = line//', non-monotonic'
      write (output_unit, '(a)') line//'  ['// &
        set_description(plan, job_param_set(plan, nint(table_value(m%results, 'job', r))))//']'
    end do
    flush (output_unit)
  end subroutine summary

end submodule voussoir_sweep_master_report
