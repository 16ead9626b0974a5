!> Thin helpers over the HDF5 Fortran API: the only place the kernel's results meet HDF5.
!>
!> A result file is built in memory (HDF5's core driver) and written to disk by
!> `h5_commit` in one checked write to `<path>.part`, then renamed over `<path>`: a
!> full disk fails that write, cleanly, and leaves any earlier file of that name as it
!> was (HDF5 itself never meets the failing disk).
!>
!> Strings are written as fixed-length, null-terminated ASCII. Every HDF5 call's error
!> code is checked: the helpers take a status, do nothing once it has failed (so a
!> writer can chain them and check once), and record the first failure with the object
!> it concerns. Handles are closed even after a failure. HDF5's own error printing is
!> turned off: the status says what went wrong, and the program says it once.
module voussoir_h5
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char, c_loc, c_ptr, c_size_t
  use, intrinsic :: iso_fortran_env, only: int8
  use hdf5
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  implicit none
  private

  public :: h5_create, h5_commit, commit_text_file, h5_open_ro, h5_close, h5_group, h5_group_close
  public :: h5_write, h5_attr, h5_rename, h5_discard, utc_now, h5_exists
  public :: h5_read_real_1d, h5_read_int_1d, h5_read_attr_string
  public :: hid_t

  !> Write a whole dataset (real or integer, rank 1 to 3).
  interface h5_write
    module procedure write_r1, write_r2, write_r3, write_i1, write_i2
  end interface h5_write

  !> Write an attribute (string, real, integer) on a file, group or dataset.
  interface h5_attr
    module procedure attr_string, attr_real, attr_int
  end interface h5_attr

  interface
    !> src/hdf5/file_write.c: writes past the file-size limit fail instead of killing.
    subroutine report_file_limits() bind(c, name='voussoir_report_file_limits')
    end subroutine report_file_limits
    !> src/hdf5/file_write.c: write bytes to a file, every error checked; 0 or errno.
    function c_write_file(path, bytes, n, message, message_len) bind(c, name='voussoir_write_file') result(rc)
      import :: c_int, c_char, c_ptr, c_size_t
      character(kind=c_char), intent(in) :: path(*)
      type(c_ptr), value :: bytes
      integer(c_size_t), value :: n, message_len
      character(kind=c_char), intent(out) :: message(*)
      integer(c_int) :: rc
    end function c_write_file
    function c_rename(old, new) bind(c, name='rename') result(rc)
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: old(*), new(*)
      integer(c_int) :: rc
    end function c_rename
  end interface

contains

  !> Record a failed HDF5 call (`err` /= 0) as the first failure of `status`.
  subroutine check(err, what, status)
    integer, intent(in) :: err
    character(len=*), intent(in) :: what
    type(status_t), intent(inout) :: status
    if (err /= 0 .and. status%ok) call fail(status, 'HDF5 error: cannot '//what)
  end subroutine check

  !> Start the library with its error printing off (the status carries the error).
  subroutine start_library()
    integer :: err, quiet
    call report_file_limits()
    call h5open_f(err)
    call h5eset_auto_f(0, quiet)
  end subroutine start_library

  !> Start the result file `path` in memory; `h5_commit` writes it.
  subroutine h5_create(path, file_id, status)
    character(len=*), intent(in) :: path
    integer(hid_t), intent(out) :: file_id
    type(status_t), intent(inout) :: status
    integer(hid_t) :: fapl
    integer :: err
    integer(size_t), parameter :: increment = 1048576_size_t   ! memory grows by 1 MiB
    file_id = -1
    if (.not. status%ok) return
    call start_library()
    call h5pcreate_f(H5P_FILE_ACCESS_F, fapl, err)
    if (err == 0) call h5pset_fapl_core_f(fapl, increment, .false., err)
    if (err == 0) call h5fcreate_f(path, H5F_ACC_TRUNC_F, file_id, err, access_prp=fapl)
    if (err /= 0) call fail(status, trim(path)//': cannot create HDF5 file (in memory)')
    call h5pclose_f(fapl, err)
  end subroutine h5_create

  !> Write the in-memory file `file_id` to `path` (through `path`.part, renamed when
  !> whole) and close it. On failure nothing is left but any earlier file at `path`,
  !> untouched, and the status says so.
  subroutine h5_commit(file_id, path, status)
    integer(hid_t), intent(in) :: file_id
    character(len=*), intent(in) :: path
    type(status_t), intent(inout) :: status
    integer(int8), allocatable, target :: image(:)
    integer(int8), target :: probe(1)
    type(c_ptr) :: buffer
    integer(size_t) :: n
    integer :: err
    if (status%ok) then
      call h5fflush_f(file_id, H5F_SCOPE_GLOBAL_F, err)
      call check(err, 'flush the file', status)
    end if
    if (status%ok) then
      buffer = c_loc(probe)
      call h5fget_file_image_f(file_id, buffer, 0_size_t, err, n)
      call check(err, 'measure the file image', status)
    end if
    if (status%ok) then
      allocate (image(n))
      buffer = c_loc(image)
      call h5fget_file_image_f(file_id, buffer, n, err)
      call check(err, 'copy the file image', status)
    end if
    call h5_close(file_id, status)
    if (status%ok) buffer = c_loc(image)
    call write_through_part(path, buffer, n, status)
  end subroutine h5_commit

  !> Write `text` to `path` the same way: whole, or not at all and the old file kept.
  subroutine commit_text_file(path, text, status)
    character(len=*), intent(in) :: path
    character(len=*), intent(in), target :: text
    type(status_t), intent(inout) :: status
    call write_through_part(path, c_loc(text), int(len(text), size_t), status)
  end subroutine commit_text_file

  !> `n` bytes at `bytes` to `path`.part, renamed to `path` when written; on any failure
  !> (here or before: `status` already failed) the .part is removed and the message says
  !> that `path` was not written.
  subroutine write_through_part(path, bytes, n, status)
    character(len=*), intent(in) :: path
    type(c_ptr), intent(in) :: bytes
    integer(size_t), intent(in) :: n
    type(status_t), intent(inout) :: status
    character(len=512) :: message
    character(len=:), allocatable :: tmp
    tmp = trim(path)//'.part'
    if (status%ok) then
      message = ''
      if (c_write_file(tmp//c_null_char, bytes, int(n, c_size_t), message, int(len(message), c_size_t)) /= 0) &
        call fail(status, message(:max(1, index(message, c_null_char) - 1)))
    end if
    if (status%ok) call h5_rename(tmp, path, status)
    if (.not. status%ok) then
      call h5_discard(tmp)
      status%message = trim(path)//': not written ('//trim(status%message)// &
                       '; disk full or not writable?); any earlier file of that name is left as it was'
    end if
  end subroutine write_through_part

  !> Open an existing `path` read-only.
  subroutine h5_open_ro(path, file_id, status)
    character(len=*), intent(in) :: path
    integer(hid_t), intent(out) :: file_id
    type(status_t), intent(inout) :: status
    integer :: err
    file_id = -1
    if (.not. status%ok) return
    call start_library()
    call h5fopen_f(path, H5F_ACC_RDONLY_F, file_id, err)
    if (err /= 0) call fail(status, trim(path)//': cannot open HDF5 file (not an HDF5 file?)')
  end subroutine h5_open_ro

  !> Close a file (always tried): data still buffered is written now, so a full disk
  !> often shows here.
  subroutine h5_close(file_id, status)
    integer(hid_t), intent(in) :: file_id
    type(status_t), intent(inout) :: status
    integer :: err
    if (file_id < 0) return
    call h5fclose_f(file_id, err)
    call check(err, 'close the file (write its buffered data)', status)
  end subroutine h5_close

  !> Open group `name` under `loc`, creating it if needed.
  subroutine h5_group(loc, name, group_id, status)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer(hid_t), intent(out) :: group_id
    type(status_t), intent(inout) :: status
    integer :: err
    group_id = -1
    if (.not. status%ok) return
    if (h5_exists(loc, name)) then
      call h5gopen_f(loc, name, group_id, err)
    else
      call h5gcreate_f(loc, name, group_id, err)
    end if
    call check(err, 'open or create group '//name, status)
  end subroutine h5_group

  !> Close a group (always tried).
  subroutine h5_group_close(group_id, status)
    integer(hid_t), intent(in) :: group_id
    type(status_t), intent(inout) :: status
    integer :: err
    if (group_id < 0) return
    call h5gclose_f(group_id, err)
    call check(err, 'close a group', status)
  end subroutine h5_group_close

  !> Whether link `name` exists under `loc`.
  logical function h5_exists(loc, name)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer :: err
    call h5lexists_f(loc, name, h5_exists, err)
    if (err /= 0) h5_exists = .false.
  end function h5_exists

  subroutine write_any(loc, name, type_id, dims, status, buf_r, buf_i)
    integer(hid_t), intent(in) :: loc, type_id
    character(len=*), intent(in) :: name
    integer(hsize_t), intent(in) :: dims(:)
    type(status_t), intent(inout) :: status
    real(dp), intent(in), optional :: buf_r(*)
    integer, intent(in), optional :: buf_i(*)
    integer(hid_t) :: space, dset
    integer :: err
    logical :: created
    if (.not. status%ok) return
    call h5screate_simple_f(size(dims), dims, space, err)
    call check(err, 'make the dataspace of dataset '//name, status)
    if (.not. status%ok) return
    call h5dcreate_f(loc, name, type_id, space, dset, err)
    created = err == 0
    call check(err, 'create dataset '//name, status)
    if (status%ok .and. product(dims) > 0) then
      if (present(buf_r)) call h5dwrite_f(dset, type_id, buf_r(1:product(dims)), dims, err)
      if (present(buf_i)) call h5dwrite_f(dset, type_id, buf_i(1:product(dims)), dims, err)
      call check(err, 'write dataset '//name, status)
    end if
    if (created) then
      call h5dclose_f(dset, err)
      call check(err, 'close dataset '//name, status)
    end if
    call h5sclose_f(space, err)
    call check(err, 'close the dataspace of dataset '//name, status)
  end subroutine write_any

  subroutine write_r1(loc, name, x, status)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: x(:)
    type(status_t), intent(inout) :: status
    call write_any(loc, name, H5T_NATIVE_DOUBLE, [int(size(x), hsize_t)], status, buf_r=x)
  end subroutine write_r1

  subroutine write_r2(loc, name, x, status)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: x(:, :)
    type(status_t), intent(inout) :: status
    call write_any(loc, name, H5T_NATIVE_DOUBLE, int(shape(x), hsize_t), status, buf_r=x)
  end subroutine write_r2

  subroutine write_r3(loc, name, x, status)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: x(:, :, :)
    type(status_t), intent(inout) :: status
    call write_any(loc, name, H5T_NATIVE_DOUBLE, int(shape(x), hsize_t), status, buf_r=x)
  end subroutine write_r3

  subroutine write_i1(loc, name, x, status)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer, intent(in) :: x(:)
    type(status_t), intent(inout) :: status
    call write_any(loc, name, H5T_NATIVE_INTEGER, [int(size(x), hsize_t)], status, buf_i=x)
  end subroutine write_i1

  subroutine write_i2(loc, name, x, status)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer, intent(in) :: x(:, :)
    type(status_t), intent(inout) :: status
    call write_any(loc, name, H5T_NATIVE_INTEGER, int(shape(x), hsize_t), status, buf_i=x)
  end subroutine write_i2

  !> Create attribute `name` of type `type_id` on `loc` (replacing one of that name) and
  !> write one value.
  subroutine write_attr(loc, name, type_id, status, value_r, value_i, value_s)
    integer(hid_t), intent(in) :: loc, type_id
    character(len=*), intent(in) :: name
    type(status_t), intent(inout) :: status
    real(dp), intent(in), optional :: value_r
    integer, intent(in), optional :: value_i
    character(len=*), intent(in), optional :: value_s
    integer(hid_t) :: space, attr
    integer :: err
    logical :: there
    if (.not. status%ok) return
    call h5screate_f(H5S_SCALAR_F, space, err)
    call check(err, 'make the dataspace of attribute '//name, status)
    if (.not. status%ok) return
    call h5aexists_f(loc, name, there, err)
    if (err == 0 .and. there) call h5adelete_f(loc, name, err)
    call check(err, 'replace attribute '//name, status)
    if (status%ok) then
      call h5acreate_f(loc, name, type_id, space, attr, err)
      call check(err, 'create attribute '//name, status)
      if (status%ok) then
        if (present(value_r)) call h5awrite_f(attr, type_id, value_r, [1_hsize_t], err)
        if (present(value_i)) call h5awrite_f(attr, type_id, value_i, [1_hsize_t], err)
        if (present(value_s)) call h5awrite_f(attr, type_id, value_s, [1_hsize_t], err)
        call check(err, 'write attribute '//name, status)
        call h5aclose_f(attr, err)
        call check(err, 'close attribute '//name, status)
      end if
    end if
    call h5sclose_f(space, err)
    call check(err, 'close the dataspace of attribute '//name, status)
  end subroutine write_attr

  subroutine attr_string(loc, name, value, status)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name, value
    type(status_t), intent(inout) :: status
    integer(hid_t) :: atype
    integer :: err
    if (.not. status%ok) return
    call h5tcopy_f(H5T_FORTRAN_S1, atype, err)
    call check(err, 'make the string type of attribute '//name, status)
    if (.not. status%ok) return
    call h5tset_size_f(atype, int(max(1, len(value)), size_t), err)
    call check(err, 'size the string type of attribute '//name, status)
    call h5tset_strpad_f(atype, H5T_STR_NULLTERM_F, err)
    call check(err, 'pad the string type of attribute '//name, status)
    if (len(value) > 0) then
      call write_attr(loc, name, atype, status, value_s=value)
    else
      call write_attr(loc, name, atype, status, value_s=' ')
    end if
    call h5tclose_f(atype, err)
    call check(err, 'close the string type of attribute '//name, status)
  end subroutine attr_string

  subroutine attr_real(loc, name, value, status)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: value
    type(status_t), intent(inout) :: status
    call write_attr(loc, name, H5T_NATIVE_DOUBLE, status, value_r=value)
  end subroutine attr_real

  subroutine attr_int(loc, name, value, status)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer, intent(in) :: value
    type(status_t), intent(inout) :: status
    call write_attr(loc, name, H5T_NATIVE_INTEGER, status, value_i=value)
  end subroutine attr_int

  !> Read a string attribute (blank if absent or unreadable: the callers compare it with
  !> what they expect and say what they found).
  function h5_read_attr_string(loc, name) result(value)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: value
    integer(hid_t) :: attr, atype, mtype
    integer(size_t) :: n
    integer :: err, e(6)
    logical :: there
    character(len=65536) :: buf
    value = ''
    call h5aexists_f(loc, name, there, err)
    if (err /= 0 .or. .not. there) return
    call h5aopen_f(loc, name, attr, e(1))
    call h5aget_type_f(attr, atype, e(2))
    call h5tget_size_f(atype, n, e(3))
    call h5tcopy_f(H5T_FORTRAN_S1, mtype, e(4))
    call h5tset_size_f(mtype, min(n, int(len(buf), size_t)), e(5))
    buf = ''
    call h5aread_f(attr, mtype, buf, [1_hsize_t], e(6))
    if (all(e == 0)) then
      n = index(buf(1:min(n, int(len(buf), size_t))), c_null_char)
      if (n > 0) buf(n:) = ' '
      value = trim(buf)
    end if
    call h5tclose_f(mtype, err)
    call h5tclose_f(atype, err)
    call h5aclose_f(attr, err)
  end function h5_read_attr_string

  !> Read a whole 1-D dataset of `type_id` into `x_r` or `x_i`.
  subroutine read_1d(loc, name, type_id, status, x_r, x_i)
    integer(hid_t), intent(in) :: loc, type_id
    character(len=*), intent(in) :: name
    type(status_t), intent(inout) :: status
    real(dp), allocatable, intent(inout), optional :: x_r(:)
    integer, allocatable, intent(inout), optional :: x_i(:)
    integer(hid_t) :: dset, space
    integer(hsize_t) :: dims(1), maxdims(1)
    integer :: err
    if (.not. status%ok) return
    call h5dopen_f(loc, name, dset, err)
    call check(err, 'open dataset '//name, status)
    if (.not. status%ok) return
    call h5dget_space_f(dset, space, err)
    call check(err, 'read the shape of dataset '//name, status)
    if (status%ok) then
      call h5sget_simple_extent_dims_f(space, dims, maxdims, err)
      if (err < 0) call check(err, 'read the shape of dataset '//name, status)
      call h5sclose_f(space, err)
    end if
    if (status%ok) then
      if (present(x_r)) then
        allocate (x_r(dims(1)))
        if (dims(1) > 0) call h5dread_f(dset, type_id, x_r, dims, err)
      else
        allocate (x_i(dims(1)))
        if (dims(1) > 0) call h5dread_f(dset, type_id, x_i, dims, err)
      end if
      call check(err, 'read dataset '//name, status)
    end if
    call h5dclose_f(dset, err)
  end subroutine read_1d

  !> Read a whole 1-D real dataset.
  subroutine h5_read_real_1d(loc, name, x, status)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    real(dp), allocatable, intent(out) :: x(:)
    type(status_t), intent(inout) :: status
    call read_1d(loc, name, H5T_NATIVE_DOUBLE, status, x_r=x)
    if (.not. allocated(x)) allocate (x(0))
  end subroutine h5_read_real_1d

  !> Read a whole 1-D integer dataset.
  subroutine h5_read_int_1d(loc, name, x, status)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer, allocatable, intent(out) :: x(:)
    type(status_t), intent(inout) :: status
    call read_1d(loc, name, H5T_NATIVE_INTEGER, status, x_i=x)
    if (.not. allocated(x)) allocate (x(0))
  end subroutine h5_read_int_1d

  !> Rename a file (atomic on one file system): results appear whole or not at all.
  subroutine h5_rename(old, new, status)
    character(len=*), intent(in) :: old, new
    type(status_t), intent(inout) :: status
    if (.not. status%ok) return
    if (c_rename(trim(old)//c_null_char, trim(new)//c_null_char) /= 0) &
      call fail(status, 'cannot rename '//trim(old)//' to '//trim(new))
  end subroutine h5_rename

  !> Remove a half-written file, if it is there (nothing to report if not).
  subroutine h5_discard(path)
    character(len=*), intent(in) :: path
    integer :: unit, ios
    logical :: there
    inquire (file=path, exist=there)
    if (.not. there) return
    open (newunit=unit, file=path, status='old', iostat=ios)
    if (ios == 0) close (unit, status='delete', iostat=ios)
  end subroutine h5_discard

  !> The current time as ISO 8601 with its offset from UTC.
  function utc_now() result(text)
    character(len=25) :: text
    character(len=8) :: d
    character(len=10) :: t
    character(len=5) :: z
    call date_and_time(d, t, z)
    text = d(1:4)//'-'//d(5:6)//'-'//d(7:8)//'T'//t(1:2)//':'//t(3:4)//':'//t(5:6)// &
           z(1:3)//':'//z(4:5)
  end function utc_now

end module voussoir_h5
