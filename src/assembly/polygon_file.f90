!> Assemblies of convex polygons read from a plain text file.
!>
!> Format: lines `block free` or `block driven` start a polygon, followed by one vertex
!> `x y` [m] a line; `#` starts a comment; blank lines are ignored. Vertices may be in
!> either orientation; the polygon must be convex. Every coordinate is finite and
!> within `max_coordinate_m` of the origin, every block at least `min_width_m` wide.
module voussoir_polygon_file
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_geometry, only: polygon_area, is_convex_ccw, overlap_depth, polygon_min_width
  use voussoir_line_reader, only: read_line
  use voussoir_text, only: itoa, fmt_significant, fmt_real
  use voussoir_assembly, only: polygon_t, assembly_t, role_voussoir, role_foundation
  implicit none
  private

  public :: polygon_reader_t, read_polygon_file, polygon_reader_init, polygon_reader_line, polygon_reader_end

  real(dp), parameter :: max_coordinate_m = 1.0e3_dp   !! as r_ext_m and width_m of &arch
  real(dp), parameter :: min_width_m = 1.0e-4_dp       !! 100 times the overlap tolerance
  real(dp), parameter :: overlap_tol_m = 1.0e-6_dp     !! blocks may interpenetrate by this much

  !> A polygon file being read: where the reader is, the blocks closed so far and the
  !> vertices of the open one.
  type :: polygon_reader_t
    character(len=:), allocatable :: path   !! for messages
    integer :: line_no = 0                  !! the last line read
    integer :: n_blocks = 0                 !! blocks started, the open one included
    integer :: block_line = 0               !! the line of the open block's `block`
    real(dp), allocatable :: xy(:, :)       !! (2, nv) the open block's vertices [m]
    type(polygon_t), allocatable :: polygons(:)  !! the blocks closed and checked
    logical, allocatable :: driven(:)       !! (n_blocks) of every block started
  end type polygon_reader_t

contains

  !> Read an assembly of convex polygons from the plain text file `path` (format above).
  subroutine read_polygon_file(path, assembly, status)
    character(len=*), intent(in) :: path
    type(assembly_t), intent(out) :: assembly
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: line
    character(len=512) :: iomsg
    integer :: unit, ios
    type(polygon_reader_t) :: reader

    open (newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=iomsg)
    if (ios /= 0) then
      call fail(status, trim(path)//': cannot open polygon file: '//trim(iomsg))
      return
    end if
    call polygon_reader_init(reader, path)
    do
      call read_line(unit, line, ios)
      if (ios /= 0) exit
      call polygon_reader_line(reader, line, status)
      if (.not. status%ok) exit
    end do
    close (unit)
    if (.not. status%ok) return
    call polygon_reader_end(reader, assembly, status)
  end subroutine read_polygon_file

  !> A reader at the start of the file `path` (named in its messages).
  subroutine polygon_reader_init(reader, path)
    type(polygon_reader_t), intent(out) :: reader
    character(len=*), intent(in) :: path
    reader%path = path
    allocate (reader%polygons(0), reader%driven(0), reader%xy(2, 0))
  end subroutine polygon_reader_init

  !> Take the next line of the file: a comment, a blank, a `block` line (closing the
  !> block before it) or a vertex of the open block.
  subroutine polygon_reader_line(reader, text, status)
    type(polygon_reader_t), intent(inout) :: reader
    character(len=*), intent(in) :: text
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: line, where
    character(len=16) :: word, mode
    integer :: k, ios
    real(dp) :: x, y

    reader%line_no = reader%line_no + 1
    where = ':'//itoa(reader%line_no)
    line = text
    k = index(line, '#')
    if (k > 0) line = line(:k - 1)
    if (len_trim(line) == 0) return
    word = ''
    read (line, *, iostat=ios) word
    if (word == 'block') then
      if (reader%n_blocks > 0) call close_polygon(reader, status)
      if (.not. status%ok) return
      read (line, *, iostat=ios) word, mode
      if (ios /= 0 .or. (mode /= 'free' .and. mode /= 'driven')) then
        call fail(status, trim(reader%path)//where//": expected 'block free' or 'block driven'")
        return
      end if
      reader%n_blocks = reader%n_blocks + 1
      reader%block_line = reader%line_no
      reader%driven = [reader%driven, mode == 'driven']
      deallocate (reader%xy)
      allocate (reader%xy(2, 0))
    else
      read (line, *, iostat=ios) x, y
      if (ios /= 0 .or. reader%n_blocks == 0) then
        call fail(status, trim(reader%path)//where//": expected a vertex 'x y' in m after a 'block' line")
        return
      end if
      call check_coordinate(trim(reader%path)//where, 'x', x, status)
      call check_coordinate(trim(reader%path)//where, 'y', y, status)
      if (.not. status%ok) return
      reader%xy = reshape([reader%xy, x, y], [2, size(reader%xy, 2) + 1])
    end if
  end subroutine polygon_reader_line

  !> The file has ended: close the last block, check the whole, and hand it over.
  subroutine polygon_reader_end(reader, assembly, status)
    type(polygon_reader_t), intent(inout) :: reader
    type(assembly_t), intent(out) :: assembly
    type(status_t), intent(inout) :: status
    integer :: nb

    associate (path => reader%path)
      nb = reader%n_blocks
      if (nb == 0) then
        call fail(status, trim(path)//': no block in polygon file')
        return
      end if
      call close_polygon(reader, status)
      if (.not. status%ok) return
      if (all(reader%driven)) then
        call fail(status, trim(path)//': every block is driven: nothing is free to move (mark blocks `block free`)')
        return
      end if
      if (.not. any(reader%driven)) then
        call fail(status, trim(path)//': no block is driven: nothing carries the assembly on the table '// &
                  '(mark the table or foundation blocks `block driven`)')
        return
      end if
      call check_overlaps(path, reader%polygons, status)
      if (.not. status%ok) return
    end associate
    assembly%n_bodies = nb
    call move_alloc(reader%polygons, assembly%polygon)
    call move_alloc(reader%driven, assembly%driven)
    allocate (assembly%role(nb))
    assembly%role = merge(role_foundation, role_voussoir, assembly%driven)
  end subroutine polygon_reader_end

  !> Check the open block (at least 3 vertices, an area, convex, wide enough), turn it
  !> counter-clockwise and add it to the closed ones.
  subroutine close_polygon(reader, status)
    type(polygon_reader_t), intent(inout) :: reader
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: id
    real(dp) :: width
    integer :: nv

    nv = size(reader%xy, 2)
    id = trim(reader%path)//':'//itoa(reader%block_line)//': block '//itoa(reader%n_blocks)
    if (nv < 3) then
      call fail(status, id//' has fewer than 3 vertices')
      return
    end if
    if (polygon_area(reader%xy) == 0.0_dp) then
      call fail(status, id//' has zero area (its vertices are on one line)')
      return
    end if
    if (polygon_area(reader%xy) < 0.0_dp) reader%xy = reader%xy(:, nv:1:-1)
    if (.not. is_convex_ccw(reader%xy)) then
      call fail(status, id//' is not a convex polygon (a vertex turns inwards, repeats, or the '// &
                'edges cross): split it into convex blocks')
      return
    end if
    width = polygon_min_width(reader%xy)
    if (width < min_width_m) then
      call fail(status, id//' is '//fmt_significant(width, 3)//' m wide at its narrowest: '// &
                'the allowed range is width >= 1e-4 m (0.1 mm; blocks touch within 1 micrometre)')
      return
    end if
    reader%polygons = [reader%polygons, polygon_t(reader%xy)]
  end subroutine close_polygon

  !> A vertex coordinate [m] is a finite number within max_coordinate_m of the origin
  !> (`place`: the file and line, for the message).
  subroutine check_coordinate(place, name, value, status)
    character(len=*), intent(in) :: place, name
    real(dp), intent(in) :: value
    type(status_t), intent(inout) :: status
    if (ieee_is_finite(value)) then
      if (abs(value) <= max_coordinate_m) return
      call fail(status, place//': vertex '//name//' = '//fmt_real(value)// &
                ' m is outside the allowed range -1000 m <= '//name//' <= 1000 m')
    else
      call fail(status, place//': vertex '//name//' = '//fmt_real(value)// &
                ' is not a finite number (allowed: -1000 m <= '//name//' <= 1000 m)')
    end if
  end subroutine check_coordinate

  !> Blocks may touch but not interpenetrate (by more than 1 micrometre).
  subroutine check_overlaps(path, polys, status)
    character(len=*), intent(in) :: path
    type(polygon_t), intent(in) :: polys(:)
    type(status_t), intent(inout) :: status
    real(dp), allocatable :: box(:, :)
    real(dp) :: depth
    integer :: i, j, nb
    nb = size(polys)
    allocate (box(4, nb))
    do i = 1, nb
      box(:, i) = [minval(polys(i)%xy(1, :)), maxval(polys(i)%xy(1, :)), minval(polys(i)%xy(2, :)), &
                   maxval(polys(i)%xy(2, :))]
    end do
    do i = 1, nb - 1
      do j = i + 1, nb
        if (box(1, j) >= box(2, i) - overlap_tol_m .or. box(1, i) >= box(2, j) - overlap_tol_m .or. &
            box(3, j) >= box(4, i) - overlap_tol_m .or. box(3, i) >= box(4, j) - overlap_tol_m) cycle
        depth = overlap_depth(polys(i)%xy, polys(j)%xy)
        if (depth > overlap_tol_m) then
          call fail(status, trim(path)//': blocks '//itoa(i)//' and '//itoa(j)//' overlap by '// &
                    fmt_significant(depth, 3)//' m: blocks may touch but not interpenetrate')
          return
        end if
      end do
    end do
  end subroutine check_overlaps

end module voussoir_polygon_file
