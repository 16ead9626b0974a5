!> Thin helpers over the HDF5 Fortran API: the only place the kernel's results meet HDF5.
!>
!> Strings are written as fixed-length, null-terminated ASCII. Errors are returned as a
!> status that names the file and the object.
module voussoir_h5
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char
  use hdf5
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  implicit none
  private

  public :: h5_create, h5_open_rw, h5_open_ro, h5_close, h5_group, h5_group_close
  public :: h5_write, h5_attr, h5_rename, utc_now, h5_exists
  public :: h5_append_real, h5_append_int, h5_read_real_1d, h5_read_int_1d, h5_read_attr_string
  public :: hid_t

  !> Write a whole dataset (real or integer, rank 1 to 3).
  interface h5_write
    module procedure write_r1, write_r2, write_r3, write_i1
  end interface h5_write

  !> Write an attribute (string, real, integer) on a file, group or dataset.
  interface h5_attr
    module procedure attr_string, attr_real, attr_int
  end interface h5_attr

  interface
    function c_rename(old, new) bind(c, name='rename') result(rc)
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: old(*), new(*)
      integer(c_int) :: rc
    end function c_rename
  end interface

contains

  !> Create (truncate) `path` for writing.
  subroutine h5_create(path, file_id, status)
    character(len=*), intent(in) :: path
    integer(hid_t), intent(out) :: file_id
    type(status_t), intent(inout) :: status
    integer :: err
    call h5open_f(err)
    call h5fcreate_f(path, H5F_ACC_TRUNC_F, file_id, err)
    if (err /= 0) call fail(status, trim(path)//': cannot create HDF5 file')
  end subroutine h5_create

  !> Open an existing `path` for reading and writing.
  subroutine h5_open_rw(path, file_id, status)
    character(len=*), intent(in) :: path
    integer(hid_t), intent(out) :: file_id
    type(status_t), intent(inout) :: status
    integer :: err, quiet
    call h5open_f(err)
    call h5eset_auto_f(0, quiet)
    call h5fopen_f(path, H5F_ACC_RDWR_F, file_id, err)
    call h5eset_auto_f(1, quiet)
    if (err /= 0) call fail(status, trim(path)//': cannot open HDF5 file for writing (not an HDF5 file?)')
  end subroutine h5_open_rw

  !> Open an existing `path` read-only.
  subroutine h5_open_ro(path, file_id, status)
    character(len=*), intent(in) :: path
    integer(hid_t), intent(out) :: file_id
    type(status_t), intent(inout) :: status
    integer :: err, quiet
    call h5open_f(err)
    call h5eset_auto_f(0, quiet)
    call h5fopen_f(path, H5F_ACC_RDONLY_F, file_id, err)
    call h5eset_auto_f(1, quiet)
    if (err /= 0) call fail(status, trim(path)//': cannot open HDF5 file (not an HDF5 file?)')
  end subroutine h5_open_ro

  subroutine h5_close(file_id)
    integer(hid_t), intent(in) :: file_id
    integer :: err
    call h5fclose_f(file_id, err)
  end subroutine h5_close

  !> Open group `name` under `loc`, creating it if needed.
  subroutine h5_group(loc, name, group_id)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer(hid_t), intent(out) :: group_id
    integer :: err
    if (h5_exists(loc, name)) then
      call h5gopen_f(loc, name, group_id, err)
    else
      call h5gcreate_f(loc, name, group_id, err)
    end if
  end subroutine h5_group

  subroutine h5_group_close(group_id)
    integer(hid_t), intent(in) :: group_id
    integer :: err
    call h5gclose_f(group_id, err)
  end subroutine h5_group_close

  !> Whether link `name` exists under `loc`.
  logical function h5_exists(loc, name)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer :: err
    call h5lexists_f(loc, name, h5_exists, err)
    if (err /= 0) h5_exists = .false.
  end function h5_exists

  subroutine write_any(loc, name, type_id, dims, buf_r, buf_i)
    integer(hid_t), intent(in) :: loc, type_id
    character(len=*), intent(in) :: name
    integer(hsize_t), intent(in) :: dims(:)
    real(dp), intent(in), optional :: buf_r(*)
    integer, intent(in), optional :: buf_i(*)
    integer(hid_t) :: space, dset
    integer :: err
    call h5screate_simple_f(size(dims), dims, space, err)
    call h5dcreate_f(loc, name, type_id, space, dset, err)
    if (product(dims) > 0) then
      if (present(buf_r)) call h5dwrite_f(dset, type_id, buf_r(1:product(dims)), dims, err)
      if (present(buf_i)) call h5dwrite_f(dset, type_id, buf_i(1:product(dims)), dims, err)
    end if
    call h5dclose_f(dset, err)
    call h5sclose_f(space, err)
  end subroutine write_any

  subroutine write_r1(loc, name, x)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: x(:)
    call write_any(loc, name, H5T_NATIVE_DOUBLE, [int(size(x), hsize_t)], buf_r=x)
  end subroutine write_r1

  subroutine write_r2(loc, name, x)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: x(:, :)
    call write_any(loc, name, H5T_NATIVE_DOUBLE, int(shape(x), hsize_t), buf_r=x)
  end subroutine write_r2

  subroutine write_r3(loc, name, x)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: x(:, :, :)
    call write_any(loc, name, H5T_NATIVE_DOUBLE, int(shape(x), hsize_t), buf_r=x)
  end subroutine write_r3

  subroutine write_i1(loc, name, x)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer, intent(in) :: x(:)
    call write_any(loc, name, H5T_NATIVE_INTEGER, [int(size(x), hsize_t)], buf_i=x)
  end subroutine write_i1

  subroutine attr_string(loc, name, value)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name, value
    integer(hid_t) :: atype, space, attr
    integer :: err
    call h5tcopy_f(H5T_FORTRAN_S1, atype, err)
    call h5tset_size_f(atype, int(max(1, len(value)), size_t), err)
    call h5tset_strpad_f(atype, H5T_STR_NULLTERM_F, err)
    call h5screate_f(H5S_SCALAR_F, space, err)
    call delete_attr(loc, name)
    call h5acreate_f(loc, name, atype, space, attr, err)
    if (len(value) > 0) then
      call h5awrite_f(attr, atype, value, [1_hsize_t], err)
    else
      call h5awrite_f(attr, atype, ' ', [1_hsize_t], err)
    end if
    call h5aclose_f(attr, err)
    call h5sclose_f(space, err)
    call h5tclose_f(atype, err)
  end subroutine attr_string

  subroutine attr_real(loc, name, value)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: value
    integer(hid_t) :: space, attr
    integer :: err
    call h5screate_f(H5S_SCALAR_F, space, err)
    call delete_attr(loc, name)
    call h5acreate_f(loc, name, H5T_NATIVE_DOUBLE, space, attr, err)
    call h5awrite_f(attr, H5T_NATIVE_DOUBLE, value, [1_hsize_t], err)
    call h5aclose_f(attr, err)
    call h5sclose_f(space, err)
  end subroutine attr_real

  subroutine attr_int(loc, name, value)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer, intent(in) :: value
    integer(hid_t) :: space, attr
    integer :: err
    call h5screate_f(H5S_SCALAR_F, space, err)
    call delete_attr(loc, name)
    call h5acreate_f(loc, name, H5T_NATIVE_INTEGER, space, attr, err)
    call h5awrite_f(attr, H5T_NATIVE_INTEGER, value, [1_hsize_t], err)
    call h5aclose_f(attr, err)
    call h5sclose_f(space, err)
  end subroutine attr_int

  subroutine delete_attr(loc, name)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    logical :: there
    integer :: err
    call h5aexists_f(loc, name, there, err)
    if (there) call h5adelete_f(loc, name, err)
  end subroutine delete_attr

  !> Read a string attribute (blank if absent).
  function h5_read_attr_string(loc, name) result(value)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: value
    integer(hid_t) :: attr, atype, mtype
    integer(size_t) :: n
    integer :: err
    logical :: there
    character(len=65536) :: buf
    value = ''
    call h5aexists_f(loc, name, there, err)
    if (.not. there) return
    call h5aopen_f(loc, name, attr, err)
    call h5aget_type_f(attr, atype, err)
    call h5tget_size_f(atype, n, err)
    call h5tcopy_f(H5T_FORTRAN_S1, mtype, err)
    call h5tset_size_f(mtype, min(n, int(len(buf), size_t)), err)
    buf = ''
    call h5aread_f(attr, mtype, buf, [1_hsize_t], err)
    n = index(buf(1:min(n, int(len(buf), size_t))), c_null_char)
    if (n > 0) buf(n:) = ' '
    value = trim(buf)
    call h5tclose_f(mtype, err)
    call h5tclose_f(atype, err)
    call h5aclose_f(attr, err)
  end function h5_read_attr_string

  !> Append values to the extendible 1-D dataset `name` (created chunked if absent).
  subroutine h5_append_real(loc, name, x)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: x(:)
    call append_any(loc, name, H5T_NATIVE_DOUBLE, size(x), buf_r=x)
  end subroutine h5_append_real

  subroutine h5_append_int(loc, name, x)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer, intent(in) :: x(:)
    call append_any(loc, name, H5T_NATIVE_INTEGER, size(x), buf_i=x)
  end subroutine h5_append_int

  subroutine append_any(loc, name, type_id, n, buf_r, buf_i)
    integer(hid_t), intent(in) :: loc, type_id
    character(len=*), intent(in) :: name
    integer, intent(in) :: n
    real(dp), intent(in), optional :: buf_r(*)
    integer, intent(in), optional :: buf_i(*)
    integer(hid_t) :: space, dset, plist, mem
    integer(hsize_t) :: dims(1), maxdims(1), start(1), count(1)
    integer :: err
    if (.not. h5_exists(loc, name)) then
      dims = 0
      maxdims = H5S_UNLIMITED_F
      call h5screate_simple_f(1, dims, space, err, maxdims)
      call h5pcreate_f(H5P_DATASET_CREATE_F, plist, err)
      call h5pset_chunk_f(plist, 1, [256_hsize_t], err)
      call h5dcreate_f(loc, name, type_id, space, dset, err, plist)
      call h5pclose_f(plist, err)
      call h5sclose_f(space, err)
    else
      call h5dopen_f(loc, name, dset, err)
    end if
    call h5dget_space_f(dset, space, err)
    call h5sget_simple_extent_dims_f(space, dims, maxdims, err)
    call h5sclose_f(space, err)
    start = dims
    count = n
    dims = dims + n
    call h5dset_extent_f(dset, dims, err)
    call h5dget_space_f(dset, space, err)
    call h5sselect_hyperslab_f(space, H5S_SELECT_SET_F, start, count, err)
    call h5screate_simple_f(1, count, mem, err)
    if (present(buf_r)) call h5dwrite_f(dset, type_id, buf_r(1:n), count, err, mem, space)
    if (present(buf_i)) call h5dwrite_f(dset, type_id, buf_i(1:n), count, err, mem, space)
    call h5sclose_f(mem, err)
    call h5sclose_f(space, err)
    call h5dclose_f(dset, err)
  end subroutine append_any

  !> Read a whole 1-D real dataset (empty if absent).
  subroutine h5_read_real_1d(loc, name, x)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    real(dp), allocatable, intent(out) :: x(:)
    integer(hid_t) :: dset, space
    integer(hsize_t) :: dims(1), maxdims(1)
    integer :: err
    if (.not. h5_exists(loc, name)) then
      allocate (x(0))
      return
    end if
    call h5dopen_f(loc, name, dset, err)
    call h5dget_space_f(dset, space, err)
    call h5sget_simple_extent_dims_f(space, dims, maxdims, err)
    allocate (x(dims(1)))
    if (dims(1) > 0) call h5dread_f(dset, H5T_NATIVE_DOUBLE, x, dims, err)
    call h5sclose_f(space, err)
    call h5dclose_f(dset, err)
  end subroutine h5_read_real_1d

  subroutine h5_read_int_1d(loc, name, x)
    integer(hid_t), intent(in) :: loc
    character(len=*), intent(in) :: name
    integer, allocatable, intent(out) :: x(:)
    integer(hid_t) :: dset, space
    integer(hsize_t) :: dims(1), maxdims(1)
    integer :: err
    if (.not. h5_exists(loc, name)) then
      allocate (x(0))
      return
    end if
    call h5dopen_f(loc, name, dset, err)
    call h5dget_space_f(dset, space, err)
    call h5sget_simple_extent_dims_f(space, dims, maxdims, err)
    allocate (x(dims(1)))
    if (dims(1) > 0) call h5dread_f(dset, H5T_NATIVE_INTEGER, x, dims, err)
    call h5sclose_f(space, err)
    call h5dclose_f(dset, err)
  end subroutine h5_read_int_1d

  !> Rename a file (atomic on one file system): results appear whole or not at all.
  subroutine h5_rename(old, new, status)
    character(len=*), intent(in) :: old, new
    type(status_t), intent(inout) :: status
    if (c_rename(trim(old)//c_null_char, trim(new)//c_null_char) /= 0) &
      call fail(status, 'cannot rename '//trim(old)//' to '//trim(new))
  end subroutine h5_rename

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
