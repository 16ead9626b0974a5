!> A worker rank of the sweep: runs the tasks rank 0 sends and returns each outcome.
module voussoir_sweep_worker
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t
  use voussoir_text, only: itoa
  use voussoir_threshold_search, only: threshold_search_t, run_outcome_t, threshold_next, &
                                       threshold_record, threshold_done
  use voussoir_sweep_plan, only: sweep_plan_t
  use voussoir_sweep_jobs, only: job_search_init
  use voussoir_sweep_comm, only: sweep_comm_t, comm_die, comm_send, comm_poll, comm_recv, nap, &
                                 tag_result, tag_stop
  use voussoir_sweep_tasks, only: queued_task_t, simulate_job, msg_of_outcome, prefetch, task_head, history_width
  implicit none
  private

  public :: worker_run

  !> The state of a worker rank.
  type :: worker_t
    type(queued_task_t) :: queue(prefetch + 1)            !! tasks received, not started
    integer :: n_queued = 0
    logical :: stopping = .false.                         !! rank 0 said stop
    type(threshold_search_t), allocatable :: replica(:)   !! searches as far as this rank knows them
    logical, allocatable :: known(:)                      !! replica(job) followed since its last sync
  end type worker_t

contains

  !> With nothing queued after a run of a search, go on with that search.
  subroutine worker_run(plan, net)
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_comm_t), intent(in) :: net
    type(worker_t) :: w
    real(dp), allocatable :: msg(:)
    integer :: job, seq
    real(dp) :: amp_m
    logical :: busy, continuing, done
    type(run_outcome_t) :: o
    type(status_t) :: status

    if (plan%mode%has_search()) allocate (w%replica(0:plan%n_jobs - 1))
    allocate (w%known(0:plan%n_jobs - 1))
    w%known = .false.
    busy = .false.
    do
      call receive_all(net, w)
      if (.not. busy) then
        if (w%n_queued == 0) then
          if (w%stopping) exit
          call nap()
          cycle
        end if
        msg = w%queue(1)%msg
        w%queue(1:w%n_queued - 1) = w%queue(2:w%n_queued)
        w%n_queued = w%n_queued - 1
        job = nint(msg(1))
        seq = nint(msg(2))
        amp_m = msg(3)
        if (plan%mode%has_search()) call sync_replica(plan, net, w, job, amp_m, msg)
        busy = .true.
      end if
      call simulate_job(plan, job, amp_m, o, status)
      if (.not. status%ok) call comm_die(net, 'rank '//itoa(net%rank)//', '//trim(status%message))
      continuing = .false.
      if (plan%mode%has_search() .and. .not. o%failed) then
        call threshold_record(w%replica(job), o, status)
        if (.not. status%ok) call comm_die(net, status%message)
        call receive_all(net, w)
        continuing = w%n_queued == 0 .and. .not. threshold_done(w%replica(job))
      end if
      call comm_send(net, 0, tag_result, msg_of_outcome(job, seq, continuing, o))
      busy = continuing
      if (continuing) then
        seq = seq + 1
        call threshold_next(w%replica(job), amp_m, done)
      end if
    end do
  end subroutine worker_run

  !> Queue every task that has arrived; note a stop.
  subroutine receive_all(net, w)
    type(sweep_comm_t), intent(in) :: net
    type(worker_t), intent(inout) :: w
    real(dp), allocatable :: msg(:)
    integer :: sender, tag, length
    logical :: waiting
    do
      call comm_poll(net, 0, waiting, sender, tag, length)
      if (.not. waiting) exit
      call comm_recv(net, 0, tag, length, msg)
      if (tag == tag_stop) then
        w%stopping = .true.
      else if (w%n_queued < size(w%queue)) then
        w%n_queued = w%n_queued + 1
        w%queue(w%n_queued)%msg = msg
      else
        call comm_die(net, 'internal: rank '//itoa(net%rank)//' got more tasks than it can hold')
      end if
    end do
  end subroutine receive_all

  !> Bring the replica of search `job` to the history the task carries; its next run
  !> must be at `amp_m`.
  subroutine sync_replica(plan, net, w, job, amp_m, task)
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_comm_t), intent(in) :: net
    type(worker_t), intent(inout) :: w
    integer, intent(in) :: job
    real(dp), intent(in) :: amp_m
    real(dp), intent(in) :: task(:)
    integer :: k, n
    real(dp) :: next_m
    logical :: done
    type(run_outcome_t) :: past
    type(status_t) :: status
    n = nint(task(4))
    if (w%known(job)) then
      if (w%replica(job)%n_runs == n) return   ! this rank made the runs since it last synced
    end if
    call job_search_init(plan, job, w%replica(job), status)
    do k = 1, n
      past%amplitude_m = task(task_head + history_width*(k - 1) + 1)
      past%collapsed = task(task_head + history_width*(k - 1) + 2) == 1.0_dp
      past%peak_crown_disp_m = task(task_head + history_width*(k - 1) + 3)
      if (status%ok) call threshold_record(w%replica(job), past, status)
    end do
    call threshold_next(w%replica(job), next_m, done)
    if (.not. status%ok .or. done .or. next_m /= amp_m) &
      call comm_die(net, 'internal: rank '//itoa(net%rank)//' cannot follow the search of job '//itoa(job))
    w%known(job) = .true.
  end subroutine sync_replica

end module voussoir_sweep_worker
