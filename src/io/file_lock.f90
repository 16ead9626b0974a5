!> One sweep per result file (file_lock.c): a lock on FILE.lock held while it runs,
!> released by the system however the process ends.
module voussoir_file_lock
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_size_t, c_null_char
  use voussoir_status, only: status_t, fail
  implicit none
  private
  public :: lock_file, unlock_file

  interface
    function c_lock(path, message, message_len) bind(c, name='voussoir_lock_file') result(fd)
      import :: c_int, c_char, c_size_t
      character(kind=c_char), intent(in) :: path(*)
      character(kind=c_char), intent(inout) :: message(*)
      integer(c_size_t), value :: message_len
      integer(c_int) :: fd
    end function c_lock
    subroutine c_unlock(fd, path) bind(c, name='voussoir_unlock_file')
      import :: c_int, c_char
      integer(c_int), value :: fd
      character(kind=c_char), intent(in) :: path(*)
    end subroutine c_unlock
  end interface

contains

  !> Lock `path` for this process: `fd` >= 0 on success. Fails when another process
  !> holds it (another sweep writes the same result file) or the lock cannot be made.
  subroutine lock_file(path, what, fd, status)
    character(len=*), intent(in) :: path, what
    integer, intent(out) :: fd
    type(status_t), intent(inout) :: status
    character(kind=c_char, len=256) :: message
    integer :: k
    message = repeat(c_null_char, len(message))
    fd = int(c_lock(trim(path)//c_null_char, message, int(len(message), c_size_t)))
    if (fd >= 0) return
    k = index(message, c_null_char) - 1
    if (k < 0) k = len(message)
    if (fd == -1) then
      call fail(status, trim(what)//': another sweep is writing it now (it holds '//trim(path)// &
                '): wait for it to finish, or give this one another &output file')
    else
      call fail(status, trim(what)//': cannot make the lock file '//trim(path)//': '//message(:k))
    end if
  end subroutine lock_file

  !> Release the lock taken by `lock_file` and remove the lock file.
  subroutine unlock_file(fd, path)
    integer, intent(inout) :: fd
    character(len=*), intent(in) :: path
    if (fd < 0) return
    call c_unlock(int(fd, c_int), trim(path)//c_null_char)
    fd = -1
  end subroutine unlock_file

end module voussoir_file_lock
