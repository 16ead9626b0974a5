!> The MPI layer of the sweep: a duplicated communicator and short messages of reals.
!>
!> Sends are nonblocking (MPI_Isend from a fixed pool of buffers that MPI owns until the
!> send completes), so no rank ever waits for a receiver: rank 0 can answer while it
!> computes and no order of sends can deadlock. An idle rank polls (MPI_Iprobe) and
!> sleeps 1 ms between polls instead of spinning in a blocking receive, which would
!> take a core from the ranks that compute when the machine is oversubscribed.
module voussoir_sweep_comm
  use, intrinsic :: iso_c_binding, only: c_int
  use, intrinsic :: iso_fortran_env, only: output_unit
  use mpi_f08
  use voussoir_kinds, only: dp
  implicit none
  private

  public :: sweep_comm_t, comm_start, comm_end, comm_abort, comm_die, comm_agree, comm_send, comm_poll, &
            comm_recv, wall_s, nap
  public :: tag_task, tag_result, tag_stop

  integer, parameter :: tag_task = 1, tag_result = 2, tag_stop = 3
  integer, parameter :: nap_us = 1000                      !! poll interval of an idle rank [us]

  !> This rank in the sweep's communicator.
  type :: sweep_comm_t
    type(MPI_Comm) :: comm
    integer :: rank = 0
    integer :: size = 1
  end type sweep_comm_t

  !> One send buffer; it must stay put until its request completes.
  type :: send_buffer_t
    real(dp), allocatable :: values(:)
  end type send_buffer_t

  ! The pool of sends in flight: allocated once, never moved while MPI holds it.
  type(send_buffer_t), allocatable, target, asynchronous, save :: buffers(:)
  type(MPI_Request), allocatable, save :: requests(:)

  interface
    function usleep(us) bind(c, name='usleep') result(rc)
      import :: c_int
      integer(c_int), value :: us
      integer(c_int) :: rc
    end function usleep
  end interface

contains

  subroutine comm_start(net)
    type(sweep_comm_t), intent(out) :: net
    call MPI_Init()
    call MPI_Comm_dup(MPI_COMM_WORLD, net%comm)
    call MPI_Comm_rank(net%comm, net%rank)
    call MPI_Comm_size(net%comm, net%size)
    ! Rank 0 has at most two tasks and a stop in flight per worker.
    allocate (buffers(3*net%size + 8), requests(3*net%size + 8))
    requests = MPI_REQUEST_NULL
  end subroutine comm_start

  !> Wait for the sends in flight, then leave MPI.
  subroutine comm_end(net)
    type(sweep_comm_t), intent(inout) :: net
    call MPI_Waitall(size(requests), requests, MPI_STATUSES_IGNORE)
    call MPI_Comm_free(net%comm)
    call MPI_Finalize()
  end subroutine comm_end

  !> Stop every rank after an error (the message was printed by the caller).
  subroutine comm_abort(net, code)
    type(sweep_comm_t), intent(in) :: net
    integer, intent(in) :: code
    flush (output_unit)
    call MPI_Abort(net%comm, code)
  end subroutine comm_abort

  !> Print `message` as the sweep's error and stop every rank.
  subroutine comm_die(net, message)
    type(sweep_comm_t), intent(in) :: net
    character(len=*), intent(in) :: message
    write (output_unit, '(a)') 'voussoir-sweep: error: '//trim(message)
    call comm_abort(net, 1)
  end subroutine comm_die

  !> Whether rank 0's `ok` holds, on every rank.
  logical function comm_agree(net, ok)
    type(sweep_comm_t), intent(in) :: net
    logical, intent(in) :: ok
    integer :: flag
    flag = merge(1, 0, ok)
    call MPI_Bcast(flag, 1, MPI_INTEGER, 0, net%comm)
    comm_agree = flag == 1
  end function comm_agree

  !> Send `msg` to `dest` without waiting for it to be received.
  subroutine comm_send(net, dest, tag, msg)
    type(sweep_comm_t), intent(in) :: net
    integer, intent(in) :: dest, tag
    real(dp), intent(in) :: msg(:)
    integer :: k, slot
    logical :: done
    slot = 0
    do k = 1, size(requests)
      if (requests(k) /= MPI_REQUEST_NULL) call MPI_Test(requests(k), done, MPI_STATUS_IGNORE)
      if (requests(k) == MPI_REQUEST_NULL) then
        slot = k
        exit
      end if
    end do
    if (slot == 0) call MPI_Waitany(size(requests), requests, slot, MPI_STATUS_IGNORE)
    buffers(slot)%values = msg
    call MPI_Isend(buffers(slot)%values, size(msg), MPI_DOUBLE_PRECISION, dest, tag, net%comm, requests(slot))
  end subroutine comm_send

  !> Whether a message from `source` (any rank if negative) is waiting: its sender, tag
  !> and length.
  subroutine comm_poll(net, source, waiting, sender, tag, length)
    type(sweep_comm_t), intent(in) :: net
    integer, intent(in) :: source
    logical, intent(out) :: waiting
    integer, intent(out) :: sender, tag, length
    type(MPI_Status) :: st
    if (source < 0) then
      call MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, net%comm, waiting, st)
    else
      call MPI_Iprobe(source, MPI_ANY_TAG, net%comm, waiting, st)
    end if
    sender = -1
    tag = -1
    length = 0
    if (waiting) then
      sender = st%MPI_SOURCE
      tag = st%MPI_TAG
      call MPI_Get_count(st, MPI_DOUBLE_PRECISION, length)
    end if
  end subroutine comm_poll

  !> Receive the message `comm_poll` announced.
  subroutine comm_recv(net, sender, tag, length, msg)
    type(sweep_comm_t), intent(in) :: net
    integer, intent(in) :: sender, tag, length
    real(dp), allocatable, intent(out) :: msg(:)
    allocate (msg(length))
    call MPI_Recv(msg, length, MPI_DOUBLE_PRECISION, sender, tag, net%comm, MPI_STATUS_IGNORE)
  end subroutine comm_recv

  real(dp) function wall_s()
    wall_s = MPI_Wtime()
  end function wall_s

  !> Let the core go for a moment (an MPI wait would spin on it).
  subroutine nap()
    integer(c_int) :: rc
    rc = usleep(int(nap_us, c_int))
  end subroutine nap

end module voussoir_sweep_comm
