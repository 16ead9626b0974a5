!> The loads of a &load group placed on the blocks of an assembly: each point load on the
!> block that contains its point (1e-9 m of tolerance on a block's boundary), the live
!> loads of an axle group and of a path on the top surface of the assembly (the highest
!> boundary point of any block at their x), the distributed dead load split into strips
!> on the blocks whose top lies under them. voussoir-limit's LP and voussoir-run's
!> set-up read the same placed loads. docs/limit_analysis.md, "Loads".
module voussoir_placed_loads
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa, fmt_significant
  use voussoir_geometry, only: cross2
  use voussoir_assembly, only: assembly_t
  use voussoir_load_config, only: load_config_t
  implicit none
  private
  public :: placed_loads_t, place_loads, block_at, top_surface, moves_on_top, vehicle_x
  public :: boundary_tol_m, dead_load_strips

  real(dp), parameter :: boundary_tol_m = 1.0e-9_dp   !! a point this close outside a block is on it
  integer, parameter :: dead_load_strips = 1000       !! strips of the distributed dead load

  !> Forces at points of the blocks: live ones (times the load factor) and dead ones.
  type :: placed_loads_t
    integer :: n = 0
    integer, allocatable :: block(:)         !! the block that carries load k
    integer, allocatable :: source(:)        !! point load j of &load, 0 for the distributed dead load
    real(dp), allocatable :: xy(:, :)        !! (2, n) point of application [m]
    real(dp), allocatable :: force_n(:, :)   !! (2, n) force [N] (a live load: at load factor 1)
    logical, allocatable :: live(:)
  end type placed_loads_t

contains

  !> Whether the live loads of `d` are placed on the top surface (an axle group or a path)
  !> rather than at their own points.
  pure logical function moves_on_top(d)
    type(load_config_t), intent(in) :: d
    moves_on_top = d%n_axles > 0 .or. d%path_points >= 2
  end function moves_on_top

  !> The vehicle's position [m]: the x of the resultant of its live loads (each live point
  !> load at its x and, in an axle group, at each of its offsets; weighted by magnitude),
  !> the point a path moves. For one live load, its own x.
  pure real(dp) function vehicle_x(d)
    type(load_config_t), intent(in) :: d
    real(dp) :: moment_nm, total_n
    integer :: j, a
    moment_nm = 0.0_dp
    total_n = 0.0_dp
    do j = 1, d%n_point_loads
      if (.not. d%point_load_live(j)) cycle
      do a = 0, d%n_axles
        total_n = total_n + d%point_load_n(j)
        moment_nm = moment_nm + d%point_load_n(j)*d%point_load_x_m(j)
        if (a > 0) moment_nm = moment_nm + d%point_load_n(j)*d%axle_spacing_m(a)
      end do
    end do
    vehicle_x = 0.0_dp
    if (total_n > 0.0_dp) vehicle_x = moment_nm/total_n
  end function vehicle_x

  !> The loads of `d` on `asm`, the live ones shifted by `shift_x_m` along x (a position on
  !> the path; 0 otherwise). A refusal starts with '&load' (the caller names the file).
  subroutine place_loads(d, asm, shift_x_m, placed, status)
    type(load_config_t), intent(in) :: d
    type(assembly_t), intent(in) :: asm
    real(dp), intent(in) :: shift_x_m
    type(placed_loads_t), intent(out) :: placed
    type(status_t), intent(inout) :: status
    real(dp) :: dir(2), p(2), x, dx, y
    integer :: j, a, b
    logical :: found

    allocate (placed%block(0), placed%source(0), placed%xy(2, 0), placed%force_n(2, 0), placed%live(0))
    do j = 1, d%n_point_loads
      dir = direction(d%point_load_dir_deg(j))
      if (d%point_load_live(j) .and. moves_on_top(d)) then
        do a = 0, d%n_axles
          x = d%point_load_x_m(j) + shift_x_m
          if (a > 0) x = x + d%axle_spacing_m(a)
          call top_surface(asm, x, y, b, found)
          if (.not. found) then
            call fail(status, '&load live point load '//itoa(j)//trim(axle_words(a))//' at x = '// &
                      fmt_significant(x, 6)//' m lies over no block (the top surface of the assembly spans '// &
                      span_text(asm)//')')
            return
          end if
          call add(b, j, [x, y], d%point_load_n(j)*dir, .true.)
        end do
      else
        p = [d%point_load_x_m(j), d%point_load_y_m(j)]
        b = block_at(asm, p)
        if (b == 0) then
          call fail(status, '&load point load '//itoa(j)//' at (x, y) = ('//fmt_significant(p(1), 6)// &
                    ', '//fmt_significant(p(2), 6)//') m lies in no block (a point on a block or on its '// &
                    'boundary, within 1e-9 m)')
          return
        end if
        call add(b, j, p, d%point_load_n(j)*dir, d%point_load_live(j))
      end if
    end do
    if (d%dead_load_n_per_m > 0.0_dp) then
      dx = (d%dead_load_x1_m - d%dead_load_x0_m)/dead_load_strips
      do j = 1, dead_load_strips
        x = d%dead_load_x0_m + (j - 0.5_dp)*dx
        call top_surface(asm, x, y, b, found)
        if (.not. found) then
          call fail(status, '&load dead_load_n_per_m from dead_load_x0_m = '// &
                    fmt_significant(d%dead_load_x0_m, 6)//' to dead_load_x1_m = '// &
                    fmt_significant(d%dead_load_x1_m, 6)//' m: no block lies under x = '// &
                    fmt_significant(x, 6)//' m (the top surface of the assembly spans '//span_text(asm)//')')
          return
        end if
        call add(b, 0, [x, y], [0.0_dp, -d%dead_load_n_per_m*dx], .false.)
      end do
    end if

  contains

    subroutine add(block, source, xy, force, live)
      integer, intent(in) :: block, source
      real(dp), intent(in) :: xy(2), force(2)
      logical, intent(in) :: live
      placed%n = placed%n + 1
      placed%block = [placed%block, block]
      placed%source = [placed%source, source]
      placed%xy = reshape([placed%xy, xy], [2, placed%n])
      placed%force_n = reshape([placed%force_n, force], [2, placed%n])
      placed%live = [placed%live, live]
    end subroutine add

  end subroutine place_loads

  !> The unit vector at `deg` from +x, exact at multiples of 90 degrees (a load straight
  !> down has no horizontal part of round-off size).
  pure function direction(deg) result(u)
    real(dp), intent(in) :: deg
    real(dp) :: u(2)
    real(dp), parameter :: pi = acos(-1.0_dp)
    u = [cos(deg*pi/180.0_dp), sin(deg*pi/180.0_dp)]
    if (modulo(deg, 90.0_dp) == 0.0_dp) u = real(nint(u), dp)
  end function direction

  function axle_words(a) result(text)
    integer, intent(in) :: a
    character(len=:), allocatable :: text
    text = ''
    if (a > 0) text = ' (axle '//itoa(a + 1)//')'
  end function axle_words

  !> 'x from a to b m' over every block.
  function span_text(asm) result(text)
    type(assembly_t), intent(in) :: asm
    character(len=:), allocatable :: text
    real(dp) :: lo, hi
    integer :: b
    lo = huge(1.0_dp)
    hi = -huge(1.0_dp)
    do b = 1, asm%n_bodies
      lo = min(lo, minval(asm%polygon(b)%xy(1, :)))
      hi = max(hi, maxval(asm%polygon(b)%xy(1, :)))
    end do
    text = 'x from '//fmt_significant(lo, 6)//' to '//fmt_significant(hi, 6)//' m'
  end function span_text

  !> The block that contains `p` (convex, counter-clockwise polygons; a point within
  !> boundary_tol_m outside counts), a free block before a driven one; 0 if none.
  pure integer function block_at(asm, p) result(found)
    type(assembly_t), intent(in) :: asm
    real(dp), intent(in) :: p(2)
    integer :: b, k, nv
    real(dp) :: e(2)
    logical :: inside
    found = 0
    do b = 1, asm%n_bodies
      associate (xy => asm%polygon(b)%xy)
        nv = size(xy, 2)
        inside = .true.
        do k = 1, nv
          e = xy(:, modulo(k, nv) + 1) - xy(:, k)
          if (cross2(e, p - xy(:, k))/norm2(e) < -boundary_tol_m) inside = .false.
        end do
      end associate
      if (.not. inside) cycle
      if (found == 0) found = b
      if (asm%driven(found) .and. .not. asm%driven(b)) found = b
    end do
  end function block_at

  !> The top surface of the assembly at `x`: the highest boundary point `y` of any block
  !> there and that `block` (a free block before a driven one at the same height).
  pure subroutine top_surface(asm, x, y, block, found)
    type(assembly_t), intent(in) :: asm
    real(dp), intent(in) :: x
    real(dp), intent(out) :: y
    integer, intent(out) :: block
    logical, intent(out) :: found
    real(dp) :: a(2), c(2), t, yk
    integer :: b, k, nv
    found = .false.
    block = 0
    y = -huge(1.0_dp)
    do b = 1, asm%n_bodies
      associate (xy => asm%polygon(b)%xy)
        nv = size(xy, 2)
        do k = 1, nv
          a = xy(:, k)
          c = xy(:, modulo(k, nv) + 1)
          if (x < min(a(1), c(1)) - boundary_tol_m .or. x > max(a(1), c(1)) + boundary_tol_m) cycle
          if (abs(c(1) - a(1)) <= boundary_tol_m) then
            yk = max(a(2), c(2))
          else
            t = min(1.0_dp, max(0.0_dp, (x - a(1))/(c(1) - a(1))))
            yk = a(2) + t*(c(2) - a(2))
          end if
          if (.not. found .or. yk > y + boundary_tol_m .or. &
              (yk >= y - boundary_tol_m .and. asm%driven(block) .and. .not. asm%driven(b))) then
            y = max(y, yk)
            block = b
            found = .true.
          end if
        end do
      end associate
    end do
  end subroutine top_surface

end module voussoir_placed_loads
