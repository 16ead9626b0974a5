!> The master's progress lines and its closing table: how a sweep reports while it runs.
submodule (voussoir_sweep_master) voussoir_sweep_master_report
  implicit none

contains

  !> A progress line every `progress_every_s` (and the last one): jobs and runs done,
  !> elapsed time, and the time left estimated from the cost of the runs still to come.
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
    if (.not. final .and. now_s - m%last_report_s < plan%progress_every_s) return
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
    if (plan%mode /= 'grid' .and. m%results%n_rows > 0) then
      runs_per_search = 0.0_dp
      do r = 1, m%results%n_rows
        runs_per_search = runs_per_search + table_value(m%results, 'n_runs', r)/m%results%n_rows
      end do
    end if
    left = 0.0_dp
    runs_left = 0.0_dp
    do job = 0, plan%n_jobs - 1
      if (m%state(job) == job_done) cycle
      if (plan%mode == 'grid') then
        runs_left = runs_left + 1.0_dp
        left = left + m%cost(job)
      else
        runs_left = runs_left + max(1.0_dp, runs_per_search - m%search(job)%n_runs)
        left = left + m%cost(job)*max(1.0_dp, runs_per_search - m%search(job)%n_runs)
      end if
    end do
    eta = '?'
    if (m%cost_done > 0.0_dp) then
      eta_s = elapsed_s*left/m%cost_done
      if (eta_s < 120.0_dp) then
        eta = itoa(nint(eta_s))//' s'
      else if (eta_s < 7200.0_dp) then
        eta = itoa(nint(eta_s/60.0_dp))//' min'
      else
        eta = fmt_fixed(eta_s/3600.0_dp, 1)//' h'
      end if
    end if
    ! Runs done / total (a threshold search's total is an estimate until it ends).
    done_runs = m%n_runs + m%n_runs_resumed
    if (plan%mode == 'grid') then
      runs = itoa(done_runs)//'/'//itoa(plan%n_jobs)//' runs'
    else
      runs = itoa(m%n_done)//'/'//itoa(plan%n_jobs)//' searches, '//itoa(done_runs)//'/~'// &
             itoa(done_runs + nint(runs_left))//' runs'
    end if
    write (output_unit, '(a)') 'voussoir-sweep: '//runs//', elapsed '//fmt_fixed(elapsed_s, 1)//' s, ETA '//trim(eta)
    flush (output_unit)
  end subroutine report

  !> The thresholds of a short sweep, for the log.
  module subroutine summary(plan, m)
    type(sweep_plan_t), intent(in) :: plan
    type(master_t), intent(in) :: m
    real(dp) :: thr
    integer :: r, job, n_runs
    character(len=160) :: line
    if (plan%mode == 'grid' .or. plan%n_jobs > max_listed_jobs) return
    do r = 1, m%results%n_rows
      job = nint(table_value(m%results, 'job', r))
      if (plan%mode == 'ida') then
        n_runs = nint(table_value(m%results, 'n_runs', r))
        if (nint(table_value(m%results, 'failed', r)) == 1) then
          write (line, '(a,i3,a)') ': FAILED (a run stopped with an error, see above), ', n_runs, ' runs'
        else if (nint(table_value(m%results, 'censored', r)) == 1) then
          write (line, '(a,i3,a)') ': stands up to scale_max, ', n_runs, ' runs'
        else
          write (line, '(a,f9.4,a,f8.3,a,i3,a)') ': threshold scale ', table_value(m%results, 'scale_threshold', r), &
            ' (PGA ', table_value(m%results, 'pga_threshold_m_s2', r)/g_m_s2, ' g), ', n_runs, ' runs'
        end if
        if (nint(table_value(m%results, 'non_monotonic', r)) == 1) line = trim(line)//', non-monotonic'
        write (output_unit, '(a)') '  '//trim(plan%records%given(job_record(plan, job)))//trim(line)//'  ['// &
          set_description(plan, job_param_set(plan, job))//']'
        cycle
      end if
      thr = table_value(m%results, 'threshold_m', r)
      n_runs = nint(table_value(m%results, 'n_runs', r))
      if (nint(table_value(m%results, 'failed', r)) == 1) then
        write (line, '(a,f7.3,a,i3,a)') '  f = ', job_frequency_hz(plan, job), ' Hz: FAILED (a run stopped with an '// &
          'error, see above), ', n_runs, ' runs'
      else if (thr == thr) then
        write (line, '(a,f7.3,a,f9.3,a,f8.3,a,i3,a)') '  f = ', job_frequency_hz(plan, job), &
          ' Hz: threshold ', 1.0e3_dp*thr, ' mm (', table_value(m%results, 'peak_accel_m_s2', r), &
          ' m/s2), ', n_runs, ' runs'
      else
        write (line, '(a,f7.3,a,i3,a)') '  f = ', job_frequency_hz(plan, job), ' Hz: stands up to amp_max_m, ', &
          n_runs, ' runs'
      end if
      if (nint(table_value(m%results, 'non_monotonic', r)) == 1) line = trim(line)//', non-monotonic'
      write (output_unit, '(a)') trim(line)//'  ['//set_description(plan, job_param_set(plan, job))//']'
    end do
    flush (output_unit)
  end subroutine summary

end submodule voussoir_sweep_master_report
