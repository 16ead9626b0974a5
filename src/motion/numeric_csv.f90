!> Numeric tables in text files: named columns of a CSV, and the number parser that
!> every record reader shares.
!>
!> A CSV has one header row naming the columns (order free, other columns ignored),
!> `#` comment lines and blank lines anywhere, and numbers in the cells. Every error
!> names the file and the line: a missing column, a short row, a cell that is not a
!> number, a NaN or an infinity. A reader that must know every column (to refuse
!> unknown ones) reads the header first (`read_csv_header`).
module voussoir_numeric_csv
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: lower, itoa
  implicit none
  private

  public :: read_csv_columns, read_csv_header, split_csv, parse_number, number_ok, number_text, number_not_finite
  public :: csv_cell_len

  integer, parameter :: line_len = 4096
  !> The length of a cell `split_csv` gives (a number, a name, a path).
  integer, parameter :: csv_cell_len = 512
  integer, parameter :: number_ok = 0          !! a finite number
  integer, parameter :: number_text = 1        !! not a number at all
  integer, parameter :: number_not_finite = 2  !! NaN or an infinity

contains

  !> The columns `names` of the CSV file `path`: `values(k, i)` is column `names(k)` of
  !> data row i, found on line `lines(i)` of the file.
  subroutine read_csv_columns(path, names, values, lines, status)
    character(len=*), intent(in) :: path
    character(len=*), intent(in) :: names(:)
    real(dp), allocatable, intent(out) :: values(:, :)
    integer, allocatable, intent(out) :: lines(:)
    type(status_t), intent(inout) :: status
    character(len=line_len) :: line
    character(len=512) :: iomsg
    character(len=csv_cell_len), allocatable :: fields(:)
    integer :: unit, ios, line_no, n, k, i, kind
    integer :: col(size(names))
    logical :: have_header

    allocate (values(size(names), 1024), lines(1024))
    open (newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=iomsg)
    if (ios /= 0) then
      call fail(status, trim(path)//': cannot open: '//trim(iomsg))
      values = values(:, 1:0)
      lines = lines(1:0)
      return
    end if
    have_header = .false.
    col = 0
    line_no = 0
    n = 0
    do
      read (unit, '(a)', iostat=ios) line
      if (ios /= 0) exit
      line_no = line_no + 1
      if (.not. is_content(line)) cycle
      call split_csv(line, fields)
      if (.not. have_header) then
        do k = 1, size(names)
          do i = 1, size(fields)
            if (fields(i) == names(k)) col(k) = i
          end do
          if (col(k) == 0) then
            call fail(status, trim(path)//':'//itoa(line_no)//': the header has no column '// &
                      trim(names(k))//' (it needs '//name_list()//')')
            exit
          end if
        end do
        if (.not. status%ok) exit
        have_header = .true.
        cycle
      end if
      if (size(fields) < maxval(col)) then
        call fail(status, trim(path)//':'//itoa(line_no)//': the row has '//itoa(size(fields))// &
                  ' cells, but column '//trim(names(maxloc(col, 1)))//' is number '//itoa(maxval(col)))
        exit
      end if
      n = n + 1
      if (n > size(lines)) call grow_rows(values, lines)
      lines(n) = line_no
      do k = 1, size(names)
        call parse_number(fields(col(k)), values(k, n), kind)
        if (kind /= number_ok) then
          call fail(status, trim(path)//':'//itoa(line_no)//': '//trim(names(k))//" = '"// &
                    trim(fields(col(k)))//"' is "//merge('not a finite number', 'not a number       ', &
                    kind == number_not_finite))
          exit
        end if
      end do
      if (.not. status%ok) exit
    end do
    close (unit)
    if (status%ok .and. .not. have_header) &
      call fail(status, trim(path)//': no header row (it needs '//name_list()//')')
    values = values(:, 1:n)
    lines = lines(1:n)

  contains

    function name_list() result(text)
      character(len=:), allocatable :: text
      integer :: j
      text = trim(names(1))
      do j = 2, size(names)
        text = text//', '//trim(names(j))
      end do
    end function name_list

  end subroutine read_csv_columns

  !> The header row of the CSV file `path` (its first line that is neither blank nor a
  !> `#` comment): its cells, as `split_csv` gives them, and its line.
  subroutine read_csv_header(path, fields, line_no, status)
    character(len=*), intent(in) :: path
    character(len=csv_cell_len), allocatable, intent(out) :: fields(:)
    integer, intent(out) :: line_no
    type(status_t), intent(inout) :: status
    character(len=line_len) :: line
    character(len=512) :: iomsg
    integer :: unit, ios

    allocate (fields(0))
    line_no = 0
    open (newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=iomsg)
    if (ios /= 0) then
      call fail(status, trim(path)//': cannot open: '//trim(iomsg))
      return
    end if
    do
      read (unit, '(a)', iostat=ios) line
      if (ios /= 0) exit
      line_no = line_no + 1
      if (.not. is_content(line)) cycle
      call split_csv(line, fields)
      exit
    end do
    close (unit)
    if (size(fields) == 0) call fail(status, trim(path)//': no header row (the file is empty or only comments)')
  end subroutine read_csv_header

  !> Whether `line` holds a row (it is neither blank nor a `#` comment).
  pure logical function is_content(line)
    character(len=*), intent(in) :: line
    integer :: first
    first = verify(line, ' '//achar(9)//achar(13))
    is_content = first > 0
    if (is_content) is_content = line(first:first) /= '#'
  end function is_content

  !> Twice the room for rows in `values` (n_columns, :) and `lines`, the rows kept.
  pure subroutine grow_rows(values, lines)
    real(dp), allocatable, intent(inout) :: values(:, :)
    integer, allocatable, intent(inout) :: lines(:)
    real(dp), allocatable :: v(:, :)
    integer, allocatable :: l(:)
    allocate (v(size(values, 1), 2*size(lines)), l(2*size(lines)))
    v(:, 1:size(lines)) = values
    l(1:size(lines)) = lines
    call move_alloc(v, values)
    call move_alloc(l, lines)
  end subroutine grow_rows

  !> Split a CSV line at commas (no quoting in numeric tables), trimming blanks and CR.
  pure subroutine split_csv(line, fields)
    character(len=*), intent(in) :: line
    character(len=csv_cell_len), allocatable, intent(out) :: fields(:)
    integer :: i, start, n, lt
    lt = len_trim(line)
    if (lt > 0) then
      if (line(lt:lt) == achar(13)) lt = lt - 1
    end if
    n = 1
    do i = 1, lt
      if (line(i:i) == ',') n = n + 1
    end do
    allocate (fields(n))
    n = 0
    start = 1
    do i = 1, lt + 1
      if (i == lt + 1) then
        n = n + 1
        fields(n) = adjustl(line(start:lt))
      else if (line(i:i) == ',') then
        n = n + 1
        fields(n) = adjustl(line(start:i - 1))
        start = i + 1
      end if
    end do
  end subroutine split_csv

  !> Read one number from `text` (blanks around it allowed). `kind` is `number_ok`,
  !> `number_text` (anything but a plain decimal or exponent number, which also catches
  !> the separators list-directed input would silently accept) or `number_not_finite`.
  subroutine parse_number(text, value, kind)
    character(len=*), intent(in) :: text
    real(dp), intent(out) :: value
    integer, intent(out) :: kind
    character(len=len(text)) :: t
    integer :: ios
    value = 0.0_dp
    t = lower(adjustl(text))
    if (index(t, 'nan') > 0 .or. index(t, 'inf') > 0) then
      kind = number_not_finite
      return
    end if
    kind = number_text
    if (len_trim(t) == 0) return
    if (verify(trim(t), '0123456789+-.ed') /= 0) return
    if (scan(t, '0123456789') == 0) return
    read (t, *, iostat=ios) value
    if (ios /= 0) return
    if (.not. ieee_is_finite(value)) then
      kind = number_not_finite
      return
    end if
    kind = number_ok
  end subroutine parse_number

end module voussoir_numeric_csv
