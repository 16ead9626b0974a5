!> A worker rank of the sweep: runs the tasks rank 0 sends and returns each outcome.
module voussoir_sweep_worker
  use, intrinsic :: iso_fortran_env, only: output_unit
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t
  use voussoir_text, only: itoa
  use voussoir_threshold_search, only: threshold_search_t, run_outcome_t, threshold_next, &
                                       threshold_record, threshold_done
  use voussoir_sweep_plan, only: sweep_plan_t
  use voussoir_sweep_jobs, only: job_search_init
  use voussoir_sweep_comm, only: sweep_comm_t, comm_abort, comm_send, comm_poll, comm_recv, nap, &
                                 tag_result, tag_stop
  use voussoir_sweep_tasks, only: queued_task_t, simulate_job, msg_of_outcome, prefetch, task_head, history_width
  implicit none
  private

  public :: worker_run

contains

  !> With nothing queued after a run of a search, go on with that search.
  subroutine worker_run(plan, net)
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_comm_t), intent(in) :: net
    type(queued_task_t) :: queue(prefetch + 1)
    type(threshold_search_t), allocatable :: replica(:)   ! searches as far as this rank knows them
    logical, allocatable :: known(:)
    real(dp), allocatable :: msg(:)
    integer :: n_queued, sender, tag, length, job, seq
    real(dp) :: amp_m
    logical :: waiting, stopping, busy, continuing, done
    type(run_outcome_t) :: o
    type(status_t) :: status

    if (plan%mode%has_search()) allocate (replica(0:plan%n_jobs - 1))
    allocate (known(0:plan%n_jobs - 1))
    known = .false.
    n_queued = 0
    stopping = .false.
    busy = .false.
    do
      call receive_all()
      if (.not. busy) then
        if (n_queued == 0) then
          if (stopping) exit
          call nap()
          cycle
        end if
        msg = queue(1)%msg
        queue(1:n_queued - 1) = queue(2:n_queued)
        n_queued = n_queued - 1
        job = nint(msg(1))
        seq = nint(msg(2))
        amp_m = msg(3)
        if (plan%mode%has_search()) call sync_replica(msg)
        busy = .true.
      end if
      call simulate_job(plan, job, amp_m, o, status)
      if (.not. status%ok) call die('rank '//itoa(net%rank)//', '//trim(status%message))
      continuing = .false.
      if (plan%mode%has_search() .and. .not. o%failed) then
        call threshold_record(replica(job), o, status)
        if (.not. status%ok) call die(status%message)
        call receive_all()
        continuing = n_queued == 0 .and. .not. threshold_done(replica(job))
      end if
      call comm_send(net, 0, tag_result, msg_of_outcome(job, seq, continuing, o))
      busy = continuing
      if (continuing) then
        seq = seq + 1
        call threshold_next(replica(job), amp_m, done)
      end if
    end do

  contains

    subroutine receive_all()
      do
        call comm_poll(net, 0, waiting, sender, tag, length)
        if (.not. waiting) exit
        call comm_recv(net, 0, tag, length, msg)
        if (tag == tag_stop) then
          stopping = .true.
        else if (n_queued < size(queue)) then
          n_queued = n_queued + 1
          queue(n_queued)%msg = msg
        else
          call die('internal: rank '//itoa(net%rank)//' got more tasks than it can hold')
        end if
      end do
    end subroutine receive_all

    !> Bring the replica of search `job` to the history the task carries.
    subroutine sync_replica(task)
      real(dp), intent(in) :: task(:)
      integer :: k, n
      real(dp) :: next_m
      type(run_outcome_t) :: past
      n = nint(task(4))
      if (known(job)) then
        if (replica(job)%n_runs == n) return   ! this rank made the runs since it last synced
      end if
      call job_search_init(plan, job, replica(job), status)
      do k = 1, n
        past%amplitude_m = task(task_head + history_width*(k - 1) + 1)
        past%collapsed = task(task_head + history_width*(k - 1) + 2) == 1.0_dp
        past%peak_crown_disp_m = task(task_head + history_width*(k - 1) + 3)
        if (status%ok) call threshold_record(replica(job), past, status)
      end do
      call threshold_next(replica(job), next_m, done)
      if (.not. status%ok .or. done .or. next_m /= amp_m) &
        call die('internal: rank '//itoa(net%rank)//' cannot follow the search of job '//itoa(job))
      known(job) = .true.
    end subroutine sync_replica

    subroutine die(message)
      character(len=*), intent(in) :: message
      write (output_unit, '(a)') 'voussoir-sweep: error: '//trim(message)
      call comm_abort(net, 1)
    end subroutine die

  end subroutine worker_run

end module voussoir_sweep_worker
