!> One line of a text file, of any length: the readers of namelists and polygon files
!> must not cut a long line (a cut line reads as another, wrong, input).
module voussoir_line_reader
  use, intrinsic :: iso_fortran_env, only: iostat_eor
  implicit none
  private

  public :: read_line

contains

  !> Read the next line of the formatted sequential `unit` into `line` (its whole
  !> length, without the line end). `iostat` is 0, or the end-of-file or error code of
  !> the read, as a plain `read (unit, '(a)')` gives it.
  subroutine read_line(unit, line, iostat, iomsg)
    integer, intent(in) :: unit
    character(len=:), allocatable, intent(out) :: line
    integer, intent(out) :: iostat
    character(len=*), intent(inout), optional :: iomsg
    character(len=1024) :: chunk
    character(len=512) :: msg
    integer :: n_read

    line = ''
    do
      read (unit, '(a)', advance='no', size=n_read, iostat=iostat, iomsg=msg) chunk
      if (iostat /= 0 .and. iostat /= iostat_eor) exit
      line = line//chunk(:n_read)
      if (iostat == iostat_eor) then
        iostat = 0
        return
      end if
    end do
    ! A last line without its line end is still a line.
    if (is_iostat_end(iostat) .and. len(line) > 0) then
      iostat = 0
      return
    end if
    if (present(iomsg) .and. iostat /= 0) iomsg = msg
  end subroutine read_line

end module voussoir_line_reader
