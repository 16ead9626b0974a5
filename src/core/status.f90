!> An error status that carries its message up to the executable.
!>
!> The kernel never stops: procedures that can fail take a `status_t`, set it with
!> `fail`, and return. Only the programs in drivers/ decide to stop.
module voussoir_status
  implicit none
  private

  public :: status_t, fail, msg_len

  integer, parameter :: msg_len = 1024

  !> Success (`ok`) or a failure with a human-readable message.
  type :: status_t
    logical :: ok = .true.
    character(len=msg_len) :: message = ''
  end type status_t

contains

  !> Mark `status` as failed with `message`.
  pure subroutine fail(status, message)
    type(status_t), intent(inout) :: status
    character(len=*), intent(in) :: message
    status%ok = .false.
    status%message = message
  end subroutine fail

end module voussoir_status
