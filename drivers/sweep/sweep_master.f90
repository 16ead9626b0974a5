!> The master of a sweep (rank 0: schedules, computes, writes); the workers are
!> drivers/sweep/sweep_worker.f90. What a job is, its rows and its texts come from the
!> plan's mode (src/sweep/sweep_mode.f90): the master never asks which mode it runs.
!>
!> Scheduling is dynamic and per run: a threshold search is a state machine that asks
!> for one run at a time, so the unit of work is one simulation whatever the mode, and
!> every search with no run in flight is ready. Rank 0 computes too: between its own
!> runs it receives the results that have arrived (MPI_Iprobe) and hands out new tasks;
!> it takes its own runs from the cheap end of the queue, the workers get the costly end.
!> Two things keep the workers busy while rank 0 is inside a run and cannot answer:
!> a worker holds up to two tasks (one running, one queued), and a task of a threshold
!> search carries the outcomes of its earlier runs, so that a worker with nothing queued
!> goes on with the same search by itself (the search is deterministic: any rank that
!> has its history proposes the same next amplitude) and tells rank 0 so with the result.
module voussoir_sweep_master
  use, intrinsic :: iso_fortran_env, only: output_unit
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_version, only: code_version
  use voussoir_config, only: config_t
  use voussoir_text, only: fmt_fixed, fmt_significant, itoa, join_words
  use voussoir_threshold_search, only: threshold_search_t, threshold_result_t, run_outcome_t, &
                                       threshold_next, threshold_record, threshold_result, threshold_done
  use voussoir_sweep_table, only: sweep_table_t, table_append, table_value, table_sort, table_row, table_set
  use voussoir_sweep_output, only: sweep_header_t, write_sweep_file, read_sweep_file, write_sweep_csv, csv_path_of
  use voussoir_ordering, only: stable_order
  use voussoir_sweep_plan, only: sweep_plan_t, set_description
  use voussoir_sweep_jobs, only: job_param_set, job_cost, job_search_init
  use voussoir_sweep_comm, only: sweep_comm_t, comm_die, comm_send, comm_poll, comm_recv, wall_s, nap, &
                                 tag_task, tag_result, tag_stop
  use voussoir_sweep_tasks, only: simulate_job, outcome_of_msg, prefetch, task_head, history_width, result_len
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use voussoir_file_lock, only: lock_file, unlock_file
  implicit none
  private

  public :: master_t, master_prepare, master_run

  integer, parameter :: job_ready = 0, job_running = 1, job_done = 2
  !> Above this many ranks rank 0 only serves: one core more matters little then, and
  !> its answers must not wait for a run of its own.
  integer, parameter :: max_ranks_computing_master = 16
  real(dp), parameter :: first_guess_runs = 12.0_dp         !! runs of a search, before any ended
  !> Longest sweep summary printed at the end [jobs].
  integer, parameter :: max_listed_jobs = 60

  !> The state of the sweep on rank 0.
  type :: master_t
    integer, allocatable :: state(:)                       !! (0:n_jobs-1) ready, running, done
    type(threshold_search_t), allocatable :: search(:)     !! (0:n_jobs-1) when jobs are searches
    logical, allocatable :: started(:)                     !! search initialised
    integer, allocatable :: order(:)                       !! jobs, costliest run first
    real(dp), allocatable :: cost(:)                       !! (0:n_jobs-1) relative cost of a run
    integer, allocatable :: outstanding(:)                 !! (1:n_ranks-1) tasks held by a worker
    integer :: front = 1, back = 0                         !! no ready job outside order(front:back)
    type(sweep_table_t) :: results, runs                   !! runs: none when jobs are single runs
    type(sweep_table_t) :: dt_check                        !! the mode's closing check (ida: runs redone at dt/2)
    type(sweep_header_t) :: header
    character(len=:), allocatable :: path, csv_path
    character(len=:), allocatable :: finished_by          !! code version of a finished file
    integer :: n_ready = 0                                 !! jobs in state ready
    integer :: n_done = 0, n_runs = 0, n_runs_resumed = 0
    integer :: n_failed = 0   !! jobs ended by a failed run (recorded, not retried)
    integer :: lock_fd = -1   !! the lock on path.lock, held while the sweep runs
    real(dp) :: t0_s = 0.0_dp, last_report_s = 0.0_dp, cost_done = 0.0_dp
    real(dp) :: busy_s = 0.0_dp                            !! wall time of the runs of this session
  end type master_t

  interface
    !> A progress line every `progress_every_s` (0: none) and the last one: jobs and runs done,
    !> elapsed time, and the time left (drivers/sweep/sweep_master_report.f90).
    module subroutine report(plan, m, n_ranks, final)
      type(sweep_plan_t), intent(in) :: plan
      type(master_t), intent(inout) :: m
      integer, intent(in) :: n_ranks
      logical, intent(in) :: final
    end subroutine report
    !> The plan's cost before it starts (drivers/sweep/sweep_master_report.f90).
    module subroutine estimate(plan, n_ranks)
      type(sweep_plan_t), intent(in) :: plan
      integer, intent(in) :: n_ranks
    end subroutine estimate
    !> The table of results at the end of a sweep (drivers/sweep/sweep_master_report.f90).
    module subroutine summary(plan, m)
      type(sweep_plan_t), intent(in) :: plan
      type(master_t), intent(in) :: m
    end subroutine summary
  end interface

contains

  !> Set up rank 0: the lock of the result file (one sweep per file), the file to write,
  !> and what an earlier run of the same sweep left in it.
  subroutine master_prepare(plan, base, n_ranks, m, status)
    type(sweep_plan_t), intent(in) :: plan
    type(config_t), intent(in) :: base
    integer, intent(in) :: n_ranks
    type(master_t), intent(out) :: m
    type(status_t), intent(inout) :: status
    m%path = trim(base%output%file)
    if (m%path == 'voussoir_run.h5') m%path = 'voussoir_sweep.h5'   ! the default is voussoir-run's
    call lock_file(m%path//'.lock', m%path, m%lock_fd, status)
    if (.not. status%ok) return
    call prepare_file(plan, base, n_ranks, m, status)
    if (.not. status%ok) call unlock_file(m%lock_fd, m%path//'.lock')
  end subroutine master_prepare

  subroutine prepare_file(plan, base, n_ranks, m, status)
    type(sweep_plan_t), intent(in) :: plan
    type(config_t), intent(in) :: base
    integer, intent(in) :: n_ranks
    type(master_t), intent(inout) :: m
    type(status_t), intent(inout) :: status
    logical :: exists
    integer :: job
    character(len=:), allocatable :: written_by

    m%csv_path = csv_path_of(m%path)
    allocate (m%state(0:plan%n_jobs - 1), m%started(0:plan%n_jobs - 1), m%cost(0:plan%n_jobs - 1), &
              m%outstanding(1:max(1, n_ranks - 1)))
    m%state = job_ready
    m%n_ready = plan%n_jobs
    m%started = .false.
    m%outstanding = 0
    if (plan%mode%has_search()) allocate (m%search(0:plan%n_jobs - 1))
    ! Costliest first, ties by job index (the order is stable).
    do job = 0, plan%n_jobs - 1
      m%cost(job) = job_cost(plan, job)
    end do
    m%order = stable_order(reshape(-m%cost, [1, plan%n_jobs])) - 1
    m%front = 1
    m%back = plan%n_jobs

    m%header%cfg = base
    m%header%cfg%output%file = m%path
    m%header%mode = plan%mode%name
    m%header%signature = plan%signature
    m%header%sweep_nml = plan%sweep_nml
    m%header%n_jobs = plan%n_jobs
    m%header%parameter_names = join_words(plan%param_names, ',')
    m%header%parameter_values = plan%param_values
    call plan%mode%file_items(plan, m%header%datasets, m%header%attributes)

    m%results = plan%mode%results_table()
    m%runs = plan%mode%runs_table()
    inquire (file=m%path, exist=exists)
    if (.not. exists) return
    call read_sweep_file(m%path, plan%signature, m%results, m%runs, written_by, status)
    if (.not. status%ok) return
    if (written_by /= code_version) then
      ! A finished sweep stays as it is; an unfinished one cannot be continued by other code.
      if (m%results%n_rows == plan%n_jobs) then
        m%finished_by = written_by
        return
      end if
      call fail(status, m%path//": was written by '"//written_by//"', this is '"//code_version// &
                "'; results of two code versions are never mixed: finish the sweep with the first "// &
                'build, or move the file away')
      return
    end if
    call restore(plan, m, status)
  end subroutine prepare_file

  !> Mark the jobs the file holds as done and replay the runs of unfinished searches.
  subroutine restore(plan, m, status)
    type(sweep_plan_t), intent(in) :: plan
    type(master_t), intent(inout) :: m
    type(status_t), intent(inout) :: status
    integer :: r, job

    do r = 1, m%results%n_rows
      job = nint(table_value(m%results, 'job', r))
      if (job < 0 .or. job >= plan%n_jobs) then
        call fail(status, m%path//': /results holds job '//itoa(job)//', outside this sweep')
        return
      else if (m%state(job) == job_done) then
        call fail(status, m%path//': /results holds job '//itoa(job)//' twice')
        return
      end if
      call set_state(m, job, job_done)
      m%n_done = m%n_done + 1
    end do
    if (plan%mode%has_search()) then
      call replay_runs(plan, m, status)
      m%n_runs_resumed = m%runs%n_rows
    else
      m%n_runs_resumed = m%results%n_rows
    end if
  end subroutine restore

  !> Replay the runs of each unfinished search in its own order: the search asks for
  !> the same amplitudes again, and continues where it stopped.
  subroutine replay_runs(plan, m, status)
    type(sweep_plan_t), intent(in) :: plan
    type(master_t), intent(inout) :: m
    type(status_t), intent(inout) :: status
    integer :: r, job, seq
    type(run_outcome_t) :: o
    real(dp) :: amp_m
    logical :: done

    call table_sort(m%runs, ['job', 'run'])
    do r = 1, m%runs%n_rows
      job = nint(table_value(m%runs, 'job', r))
      seq = nint(table_value(m%runs, 'run', r))
      if (job < 0 .or. job >= plan%n_jobs) then
        call fail(status, m%path//': /runs holds job '//itoa(job)//', outside this sweep')
        return
      end if
      if (m%state(job) == job_done) cycle
      call start_search(plan, m, job, status)
      if (.not. status%ok) return
      call threshold_next(m%search(job), amp_m, done)
      o = outcome_from_row(m%runs, r, plan%mode%value_name())
      if (done .or. seq /= m%search(job)%n_runs .or. o%amplitude_m /= amp_m .and. .not. o%failed) then
        call fail(status, m%path//': run '//itoa(seq)//' of job '//itoa(job)// &
                  ' does not follow the search of this input; the file cannot be continued')
        return
      end if
      if (o%failed) then
        call finish_search(plan, m, job, failed=.true.)
        cycle
      end if
      call threshold_record(m%search(job), o, status)
      if (.not. status%ok) return
      if (threshold_done(m%search(job))) call finish_search(plan, m, job)
    end do
  end subroutine replay_runs

  !> The sweep on rank 0: serve the workers, compute, write, report.
  subroutine master_run(plan, net, m)
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_comm_t), intent(in) :: net
    type(master_t), intent(inout) :: m
    integer :: job, w
    logical :: found, got

    m%t0_s = wall_s()
    m%last_report_s = m%t0_s
    call announce(plan, net, m)
    if (allocated(m%finished_by)) then
      write (output_unit, '(a)') 'voussoir-sweep: '//m%path//' is complete, written by '//m%finished_by// &
        '; nothing to do (move it away to recompute it with this build)'
      do w = 1, net%size - 1
        call comm_send(net, w, tag_stop, [0.0_dp])
      end do
      call unlock_file(m%lock_fd, m%path//'.lock')
      return
    end if
    if (m%n_done < plan%n_jobs) call write_state(net, m, .false.)

    call hand_out(plan, net, m)
    do while (m%n_done < plan%n_jobs)
      call serve(plan, net, m, got)
      if (got) call write_state(net, m, .false.)
      if (m%n_done == plan%n_jobs) exit
      found = .false.
      if (net%size <= max_ranks_computing_master) call pick(m, .false., job, found)
      if (found) then
        call run_own(plan, net, m, job)
        call write_state(net, m, .false.)
      else
        call nap()
      end if
      call report(plan, m, net%size, .false.)
    end do
    do w = 1, net%size - 1
      call comm_send(net, w, tag_stop, [0.0_dp])
    end do
    call close_sweep(plan, net, m)
  end subroutine master_run

  !> What the sweep is, on how many ranks, and what a resumed file kept.
  subroutine announce(plan, net, m)
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_comm_t), intent(in) :: net
    type(master_t), intent(in) :: m
    write (output_unit, '(a)') 'voussoir-sweep: '//trim(plan%mode%name)//' sweep of '//itoa(plan%n_jobs)// &
      ' jobs ('//plan%mode%jobs_text(plan)//') on '//itoa(net%size)//' ranks -> '//m%path
    call estimate(plan, net%size)
    if (allocated(plan%note)) then
      if (len(plan%note) > 0) write (output_unit, '(a)') 'voussoir-sweep: '//plan%note
    end if
    ! Said, so that a quiet sweep is not taken for a hung one (issue 26).
    if (plan%progress_every_s == 0.0_dp) write (output_unit, '(a)') 'voussoir-sweep: progress_every_s = 0: '// &
      'no progress lines; the final done: line only'
    if (m%n_done > 0 .or. m%n_runs_resumed > 0) write (output_unit, '(a)') 'voussoir-sweep: resuming '// &
      m%path//': '//itoa(m%n_done)//' of '//itoa(plan%n_jobs)//' jobs done, '//itoa(m%n_runs_resumed)// &
      ' runs kept'
    flush (output_unit)
  end subroutine announce

  !> Every job done: the mode's closing check, the complete file, the CSV, the report.
  subroutine close_sweep(plan, net, m)
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_comm_t), intent(in) :: net
    type(master_t), intent(inout) :: m
    type(status_t) :: status
    character(len=:), allocatable :: line
    call table_sort(m%results, ['job'])
    call table_sort(m%runs, ['job', 'run'])
    call plan%mode%closing_check(plan, m%results, m%dt_check, line, status)
    if (.not. status%ok) call comm_die(net, status%message)
    if (len(line) > 0) then
      write (output_unit, '(a)') 'voussoir-sweep: '//line
      flush (output_unit)
    end if
    call write_state(net, m, .true.)
    call write_sweep_csv(m%csv_path, plan, m%results, status)
    if (.not. status%ok) call comm_die(net, status%message)
    call report(plan, m, net%size, .true.)
    call summary(plan, m)
    call unlock_file(m%lock_fd, m%path//'.lock')
  end subroutine close_sweep

  !> A run of job `job` on rank 0.
  subroutine run_own(plan, net, m, job)
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_comm_t), intent(in) :: net
    type(master_t), intent(inout) :: m
    integer, intent(in) :: job
    type(status_t) :: status
    integer :: seq
    real(dp) :: amp_m
    type(run_outcome_t) :: o
    call next_run(plan, m, job, seq, amp_m)
    call set_state(m, job, job_running)
    call simulate_job(plan, job, amp_m, o, status)
    if (.not. status%ok) call comm_die(net, 'rank 0, '//trim(status%message))
    call take_result(plan, m, job, seq, o, .false., status)
    if (.not. status%ok) call comm_die(net, status%message)
  end subroutine run_own

  !> Write the whole file as it stands (`complete`: the sweep is finished).
  subroutine write_state(net, m, complete)
    type(sweep_comm_t), intent(in) :: net
    type(master_t), intent(in) :: m
    logical, intent(in) :: complete
    type(status_t) :: status
    if (allocated(m%dt_check%names)) then
      call write_sweep_file(m%path, m%header, m%results, m%runs, complete, status, m%dt_check)
    else
      call write_sweep_file(m%path, m%header, m%results, m%runs, complete, status)
    end if
    if (.not. status%ok) call comm_die(net, status%message)
  end subroutine write_state

  !> Receive every result that has arrived, then refill the workers.
  subroutine serve(plan, net, m, got)
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_comm_t), intent(in) :: net
    type(master_t), intent(inout) :: m
    logical, intent(out) :: got
    real(dp), allocatable :: msg(:)
    logical :: waiting, continuing
    integer :: sender, tag, length
    type(status_t) :: status
    got = .false.
    do
      call comm_poll(net, -1, waiting, sender, tag, length)
      if (.not. waiting) exit
      call comm_recv(net, sender, tag, length, msg)
      if (tag /= tag_result .or. length /= result_len) cycle
      ! A worker that goes on with the same search keeps its task.
      continuing = msg(3) == 1.0_dp
      if (.not. continuing) m%outstanding(sender) = m%outstanding(sender) - 1
      call take_result(plan, m, nint(msg(1)), nint(msg(2)), outcome_of_msg(msg), continuing, status)
      if (.not. status%ok) call comm_die(net, status%message)
      got = .true.
    end do
    call hand_out(plan, net, m)
  end subroutine serve

  !> Give each worker up to `prefetch` tasks, costliest first; a second task only while
  !> one more stays ready for rank 0.
  subroutine hand_out(plan, net, m)
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_comm_t), intent(in) :: net
    type(master_t), intent(inout) :: m
    integer :: slot, w, job, seq, k
    real(dp) :: amp_m
    real(dp), allocatable :: msg(:)
    logical :: found
    do slot = 1, prefetch
      do w = 1, net%size - 1
        if (m%outstanding(w) >= slot) cycle
        if (slot > 1 .and. m%n_ready <= 1) return
        call pick(m, .true., job, found)
        if (.not. found) return
        call next_run(plan, m, job, seq, amp_m)
        call set_state(m, job, job_running)
        m%outstanding(w) = m%outstanding(w) + 1
        allocate (msg(task_head + history_width*seq))
        msg(1:task_head) = [real(job, dp), real(seq, dp), amp_m, real(seq, dp)]
        do k = 1, seq
          associate (o => m%search(job)%runs(k))
            msg(task_head + history_width*(k - 1) + 1:task_head + history_width*k) = &
              [o%amplitude_m, merge(1.0_dp, 0.0_dp, o%collapsed), o%peak_crown_disp_m]
          end associate
        end do
        call comm_send(net, w, tag_task, msg)
        deallocate (msg)
      end do
    end do
  end subroutine hand_out

  !> A ready job: the costliest (for a worker) or the cheapest (for rank 0).
  subroutine pick(m, costliest, job, found)
    type(master_t), intent(inout) :: m
    logical, intent(in) :: costliest
    integer, intent(out) :: job
    logical, intent(out) :: found
    integer :: k
    ! Done jobs never become ready again: the ends of the order move inwards past them.
    do while (m%front <= m%back)
      if (m%state(m%order(m%front)) /= job_done) exit
      m%front = m%front + 1
    end do
    do while (m%back >= m%front)
      if (m%state(m%order(m%back)) /= job_done) exit
      m%back = m%back - 1
    end do
    found = .false.
    do k = 0, m%back - m%front
      job = m%order(merge(m%front + k, m%back - k, costliest))
      if (m%state(job) == job_ready) then
        found = .true.
        return
      end if
    end do
    job = -1
  end subroutine pick

  !> Move job `job` to state `new`, keeping count of the ready ones.
  subroutine set_state(m, job, new)
    type(master_t), intent(inout) :: m
    integer, intent(in) :: job, new
    if (m%state(job) == job_ready) m%n_ready = m%n_ready - 1
    if (new == job_ready) m%n_ready = m%n_ready + 1
    m%state(job) = new
  end subroutine set_state

  !> Sequence number and amplitude of the next run of a ready job.
  subroutine next_run(plan, m, job, seq, amp_m)
    type(sweep_plan_t), intent(in) :: plan
    type(master_t), intent(inout) :: m
    integer, intent(in) :: job
    integer, intent(out) :: seq
    real(dp), intent(out) :: amp_m
    logical :: done
    type(status_t) :: status
    if (plan%mode%has_search()) then
      call start_search(plan, m, job, status)   ! checked when the plan was read
      seq = m%search(job)%n_runs
      call threshold_next(m%search(job), amp_m, done)
    else
      seq = 0
      amp_m = plan%mode%run_value(plan, job)
    end if
  end subroutine next_run

  subroutine start_search(plan, m, job, status)
    type(sweep_plan_t), intent(in) :: plan
    type(master_t), intent(inout) :: m
    integer, intent(in) :: job
    type(status_t), intent(inout) :: status
    if (m%started(job)) return
    call job_search_init(plan, job, m%search(job), status)
    m%started(job) = .true.
  end subroutine start_search

  !> Record the outcome of run `seq` of job `job`; `continuing`: the rank that made it
  !> goes on with the same search.
  subroutine take_result(plan, m, job, seq, o, continuing, status)
    type(sweep_plan_t), intent(in) :: plan
    type(master_t), intent(inout) :: m
    integer, intent(in) :: job, seq
    type(run_outcome_t), intent(in) :: o
    logical, intent(in) :: continuing
    type(status_t), intent(inout) :: status
    real(dp), allocatable :: row(:)
    m%n_runs = m%n_runs + 1
    m%cost_done = m%cost_done + m%cost(job)
    m%busy_s = m%busy_s + o%wall_time_s
    if (.not. plan%mode%has_search()) then
      call finish_job(plan, m, job, o, threshold_result_t(), o%failed)
      return
    end if
    if (seq /= m%search(job)%n_runs) then
      call fail(status, 'internal: run '//itoa(seq)//' of job '//itoa(job)//' arrived out of order')
      return
    end if
    call table_row(m%runs, row)
    call table_set(m%runs, row, 'job', real(job, dp))
    call table_set(m%runs, row, 'run', real(seq, dp))
    call table_set(m%runs, row, plan%mode%value_name(), o%amplitude_m)
    call table_set(m%runs, row, 'collapsed', merge(1.0_dp, 0.0_dp, o%collapsed))
    call table_set(m%runs, row, 'collapse_time_s', o%collapse_time_s)
    call table_set(m%runs, row, 'peak_crown_disp_m', o%peak_crown_disp_m)
    call table_set(m%runs, row, 'mean_iterations', o%mean_iterations)
    call table_set(m%runs, row, 'n_steps', real(o%n_steps, dp))
    call table_set(m%runs, row, 'nonconverged_steps', real(o%nonconverged_steps, dp))
    call table_set(m%runs, row, 'wall_time_s', o%wall_time_s)
    call table_set(m%runs, row, 'failed', merge(1.0_dp, 0.0_dp, o%failed))
    call table_append(m%runs, row)
    if (o%failed) then
      call finish_search(plan, m, job, failed=.true.)
      return
    end if
    call threshold_record(m%search(job), o, status)
    if (.not. status%ok) return
    if (threshold_done(m%search(job))) then
      call finish_search(plan, m, job)
    else if (continuing) then
      call set_state(m, job, job_running)
    else
      call set_state(m, job, job_ready)
    end if
  end subroutine take_result

  !> The /results row of a finished search; `failed`: ended by a run that failed (its
  !> threshold columns NaN, its stand the last one before the failure, NaN if none, its
  !> `failed` column 1).
  subroutine finish_search(plan, m, job, failed)
    type(sweep_plan_t), intent(in) :: plan
    type(master_t), intent(inout) :: m
    integer, intent(in) :: job
    logical, intent(in), optional :: failed
    type(threshold_result_t) :: r
    logical :: broken
    real(dp) :: nan
    broken = .false.
    if (present(failed)) broken = failed
    r = threshold_result(m%search(job))
    if (broken) then
      nan = ieee_value(1.0_dp, ieee_quiet_nan)
      r%threshold_m = nan
      r%full_cycle_accel_m_s2 = nan
      if (.not. r%stand_below_m > 0.0_dp) r%stand_below_m = nan  ! no stand before the failure
      r%n_runs = r%n_runs + 1
    end if
    call finish_job(plan, m, job, run_outcome_t(), r, broken)
  end subroutine finish_search

  !> Job `job` is done: its /results row, from the outcome `o` of its single run or the
  !> result `r` of its search (the mode fills it).
  subroutine finish_job(plan, m, job, o, r, failed)
    type(sweep_plan_t), intent(in) :: plan
    type(master_t), intent(inout) :: m
    integer, intent(in) :: job
    type(run_outcome_t), intent(in) :: o
    type(threshold_result_t), intent(in) :: r
    logical, intent(in) :: failed
    real(dp), allocatable :: row(:)
    call table_row(m%results, row)
    call table_set(m%results, row, 'failed', merge(1.0_dp, 0.0_dp, failed))
    call plan%mode%result_row(plan, job, o, r, failed, m%results, row)
    call table_append(m%results, row)
    if (failed) m%n_failed = m%n_failed + 1
    call set_state(m, job, job_done)
    m%n_done = m%n_done + 1
  end subroutine finish_job

  !> The outcome stored in row `r` of a /runs table.
  function outcome_from_row(t, r, searched) result(o)
    type(sweep_table_t), intent(in) :: t
    integer, intent(in) :: r
    character(len=*), intent(in) :: searched   !! name of the searched variable's column
    type(run_outcome_t) :: o
    o%amplitude_m = value(searched)
    o%collapsed = nint(value('collapsed')) == 1
    o%collapse_time_s = value('collapse_time_s')
    o%peak_crown_disp_m = value('peak_crown_disp_m')
    o%mean_iterations = value('mean_iterations')
    o%n_steps = nint(value('n_steps'))
    o%nonconverged_steps = nint(value('nonconverged_steps'))
    o%wall_time_s = value('wall_time_s')
    o%failed = nint(value('failed')) == 1
  contains
    real(dp) function value(name)
      character(len=*), intent(in) :: name
      value = table_value(t, name, r)
    end function value
  end function outcome_from_row

end module voussoir_sweep_master
