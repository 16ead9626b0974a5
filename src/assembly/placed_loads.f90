!> The loads of a &load group placed on the blocks of an assembly: each point load on the
!> block that contains its point (1e-9 m of tolerance on a block's boundary), the live
!> loads of an axle group and of a path on the top surface of the assembly (the highest
!> boundary point of any block at their x), a live patch split into strips on the blocks
!> under it (spread through the fill where there is one), the distributed dead load split
!> into strips on the blocks whose top lies under them; with `&bridge dispersion =
!> 'boussinesq'` a live load spread by Flamant's stress (voussoir_flamant), truncated and
!> scaled to the load. voussoir-limit's LP and voussoir-run's set-up read the same placed
!> loads. docs/limit_analysis.md, "Loads"; docs/bridges.md, "Boussinesq dispersion".
module voussoir_placed_loads
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa, fmt_significant
  use voussoir_geometry, only: polygon_area, polygon_centroid, polygon_polar_moment
  use voussoir_assembly, only: assembly_t
  use voussoir_load_config, only: load_config_t
  use voussoir_flamant, only: flamant_pressure, flamant_force
  use voussoir_ordering, only: stable_order
  use voussoir_top_surface, only: boundary_tol_m, block_at, top_surface, span_text
  implicit none
  private
  public :: placed_loads_t, place_loads, block_at, top_surface, moves_on_top, vehicle_x, fill_column
  public :: boundary_tol_m, dead_load_strips, dispersion_strips, boussinesq_cutoff
  public :: kind_point, kind_dead_strip, kind_fill, kind_dispersed, kind_patch

  integer, parameter :: dead_load_strips = 1000       !! strips of the distributed dead load
  integer, parameter :: dispersion_strips = 200       !! strips of a live load spread through the fill
  !> Boussinesq's spread ends where Flamant's stress on the blocks' top falls to this
  !> fraction of the stress beneath the load (or at the ends of the deck); the strips are
  !> then scaled to sum to the load.
  real(dp), parameter :: boussinesq_cutoff = 1.0e-3_dp
  integer, parameter :: deck_samples = 4000          !! where the spread's ends are looked for
  integer, parameter :: kind_point = 1       !! a point load of &load where it stands
  integer, parameter :: kind_dead_strip = 2  !! a strip of &load's distributed dead load
  integer, parameter :: kind_fill = 3        !! the weight of the fill above one top face of a block
  integer, parameter :: kind_dispersed = 4   !! a strip of a live load spread through the fill
  integer, parameter :: kind_patch = 5       !! a strip of a live patch on the top surface (no fill)

  !> Forces at points of the blocks: live ones (times the load factor) and dead ones.
  type :: placed_loads_t
    integer :: n = 0
    integer, allocatable :: block(:)         !! the block that carries load k
    integer, allocatable :: source(:)        !! point load j of &load, 0 for the distributed dead load
    real(dp), allocatable :: xy(:, :)        !! (2, n) point of application [m]
    real(dp), allocatable :: force_n(:, :)   !! (2, n) force [N] (a live load: at load factor 1)
    logical, allocatable :: live(:)
    integer, allocatable :: kind(:)          !! kind_point, kind_dead_strip, kind_fill or kind_dispersed
    !> With a fill: each live load as it stands on the fill's surface (its strips on the
    !> blocks are the kind_dispersed loads), and the extent of x it spreads over. Without
    !> one: each live patch where its centre stands on the top surface (its strips the
    !> kind_patch loads) and the x it covers.
    logical :: surface_on_fill = .false.           !! the surface loads stand on a fill
    integer :: n_surface = 0
    integer, allocatable :: surface_source(:)      !! point load j of &load
    real(dp), allocatable :: surface_xy(:, :)      !! (2, n_surface) on the fill surface [m]
    real(dp), allocatable :: surface_force_n(:, :) !! (2, n_surface) at load factor 1 [N]
    real(dp), allocatable :: surface_spread_x_m(:, :) !! (2, n_surface) from x to x on the blocks [m]
    real(dp), allocatable :: surface_patch_m(:)    !! (n_surface) the patch's length on the surface [m]
    !> Spread by Boussinesq (Flamant's stress) rather than at an angle: each surface load's
    !> strips are its `surface_strips` placed loads from `surface_first`, equal lengths
    !> along x between its spread's ends, and `surface_retained` the fraction of the load
    !> Flamant's stress puts between those ends (the strips scaled by its inverse).
    logical :: surface_boussinesq = .false.
    integer, allocatable :: surface_first(:), surface_strips(:)
    real(dp), allocatable :: surface_retained(:)
    real(dp), allocatable :: surface_edges_x_m(:)  !! each one's surface_strips + 1 strip ends, in turn [m]
    !> With a fill's horizontal pressure: one bounded force per top face of a free block,
    !> horizontal, into the block, between the active and the mobilised passive resultant.
    integer :: n_pressure = 0
    integer, allocatable :: pressure_block(:)
    real(dp), allocatable :: pressure_xy(:, :)      !! (2, n_pressure) where it acts [m]
    real(dp), allocatable :: pressure_dir(:, :)     !! (2, n_pressure) unit, horizontal, into the block
    real(dp), allocatable :: pressure_lo_n(:), pressure_hi_n(:)  !! active and mobilised passive [N]
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

    placed%surface_on_fill = asm%has_fill
    placed%surface_boussinesq = asm%has_fill .and. asm%dispersion_boussinesq
    allocate (placed%surface_first(0), placed%surface_strips(0), placed%surface_retained(0), &
              placed%surface_edges_x_m(0))
    allocate (placed%block(0), placed%source(0), placed%xy(2, 0), placed%force_n(2, 0), placed%live(0), &
              placed%kind(0), placed%surface_source(0), placed%surface_xy(2, 0), placed%surface_force_n(2, 0), &
              placed%surface_spread_x_m(2, 0), placed%surface_patch_m(0), placed%pressure_block(0), placed%pressure_xy(2, 0), &
              placed%pressure_dir(2, 0), placed%pressure_lo_n(0), placed%pressure_hi_n(0))
    do j = 1, d%n_point_loads
      dir = direction(d%point_load_dir_deg(j))
      if (d%point_load_live(j) .and. asm%has_fill) then
        ! On the fill's surface at its x, spread through the fill onto the blocks.
        if (d%point_load_dir_deg(j) /= -90.0_dp) then
          call fail(status, '&load point_load_dir_deg('//itoa(j)//') = '//fmt_significant(d%point_load_dir_deg(j), 6)// &
                    ': with a fill the live loads stand on its surface and spread down through it: give them '// &
                    'straight down (-90)')
          return
        end if
        do a = 0, d%n_axles
          x = d%point_load_x_m(j) + shift_x_m
          if (a > 0) x = x + d%axle_spacing_m(a)
          call disperse_load(asm, placed, j, a, x, d%point_load_n(j), d%point_load_patch_m(j), status)
          if (.not. status%ok) return
        end do
      else if (d%point_load_live(j) .and. moves_on_top(d)) then
        do a = 0, d%n_axles
          x = d%point_load_x_m(j) + shift_x_m
          if (a > 0) x = x + d%axle_spacing_m(a)
          if (d%point_load_patch_m(j) > 0.0_dp) then
            call disperse_load(asm, placed, j, a, x, d%point_load_n(j), d%point_load_patch_m(j), status)
            if (.not. status%ok) return
            cycle
          end if
          call top_surface(asm, x, y, b, found)
          if (.not. found) then
            call fail(status, '&load live point load '//itoa(j)//trim(axle_words(a))//' at x = '// &
                      fmt_significant(x, 6)//' m lies over no block (the top surface of the assembly spans '// &
                      span_text(asm)//')')
            return
          end if
          call add_load(placed, b, j, [x, y], d%point_load_n(j)*dir, .true., kind_point)
        end do
      else if (d%point_load_patch_m(j) > 0.0_dp) then
        call fail(status, '&load point_load_patch_m('//itoa(j)//') = '//fmt_significant(d%point_load_patch_m(j), 6)// &
                  ' m: a patch stands on the top surface, where a path (path_points >= 2), axle_spacing_m or a '// &
                  'fill puts the live loads; here load '//itoa(j)//' acts at its point: give it a path, or '// &
                  'point_load_patch_m = 0')
        return
      else
        p = [d%point_load_x_m(j), d%point_load_y_m(j)]
        b = block_at(asm, p)
        if (b == 0) then
          call fail(status, '&load point load '//itoa(j)//' at (x, y) = ('//fmt_significant(p(1), 6)// &
                    ', '//fmt_significant(p(2), 6)//') m lies in no block (a point on a block or on its '// &
                    'boundary, within 1e-9 m)')
          return
        end if
        call add_load(placed, b, j, p, d%point_load_n(j)*dir, d%point_load_live(j), kind_point)
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
        call add_load(placed, b, 0, [x, y], [0.0_dp, -d%dead_load_n_per_m*dx], .false., kind_dead_strip)
      end do
    end if
    if (asm%has_fill) call add_fill_weight(asm, placed)
    if (asm%has_fill .and. asm%fill_passive_k > 0.0_dp) call add_fill_pressure(asm, placed)

  end subroutine place_loads

  !> Append one load to `placed`.
  pure subroutine add_load(placed, block, source, xy, force, live, kind)
    type(placed_loads_t), intent(inout) :: placed
    integer, intent(in) :: block, source, kind
    real(dp), intent(in) :: xy(2), force(2)
    logical, intent(in) :: live
    placed%n = placed%n + 1
    placed%block = [placed%block, block]
    placed%source = [placed%source, source]
    placed%xy = reshape([placed%xy, xy], [2, placed%n])
    placed%force_n = reshape([placed%force_n, force], [2, placed%n])
    placed%live = [placed%live, live]
    placed%kind = [placed%kind, kind]
  end subroutine add_load

  !> Live load j (axle a) of `magnitude_n`, a patch of `patch_m` along x centred on `x0`
  !> (0: a point): on the fill's surface of `asm`, spread either side at the dispersion
  !> angle from the vertical, from the patch's ends down to where those lines meet the top
  !> of the blocks, uniformly along x in between (dispersion_strips strips on the top
  !> surface); at angle 0, or without a fill, over the patch on the top surface beneath
  !> it; a point at angle 0: the whole load on the top surface beneath it.
  subroutine disperse_load(asm, placed, j, a, x0, magnitude_n, patch_m, status)
    type(assembly_t), intent(in) :: asm
    type(placed_loads_t), intent(inout) :: placed
    integer, intent(in) :: j, a
    real(dp), intent(in) :: x0, magnitude_n, patch_m
    type(status_t), intent(inout) :: status
    real(dp) :: x_lo, x_hi, dx, xs, ys, y0
    integer :: k, blk, side, kind
    logical :: ok
    do side = -1, 1, 2   ! both ends of the patch (a point: x0 twice)
      call top_surface(asm, x0 + side*0.5_dp*patch_m, ys, blk, ok)
      if (.not. ok) then
        call fail(status, '&load live point load '//itoa(j)//trim(axle_words(a))//' at x = '// &
                  fmt_significant(x0, 6)//' m'//trim(patch_words(patch_m))//' stands over no block (the top '// &
                  'surface of the assembly spans '//span_text(asm)//')')
        return
      end if
    end do
    if (placed%surface_boussinesq) then
      call boussinesq_load(asm, placed, j, a, x0, magnitude_n, patch_m, status)
      return
    end if
    call top_surface(asm, x0, y0, blk, ok)
    x_lo = spread_end(asm, x0 - 0.5_dp*patch_m, -1.0_dp)
    x_hi = spread_end(asm, x0 + 0.5_dp*patch_m, 1.0_dp)
    if (x_lo <= -huge(1.0_dp) .or. x_hi >= huge(1.0_dp)) then
      call fail(status, '&load live point load '//itoa(j)//trim(axle_words(a))//' at x = '//fmt_significant(x0, 6)// &
                ' m spreads through the fill beyond the ends of the bridge ('//span_text(asm)//'): move it in, or '// &
                'lower &bridge dispersion_angle_deg')
      return
    end if
    kind = merge(kind_dispersed, kind_patch, asm%has_fill)
    placed%n_surface = placed%n_surface + 1
    placed%surface_source = [placed%surface_source, j]
    placed%surface_xy = reshape([placed%surface_xy, x0, merge(asm%fill_level_m, y0, asm%has_fill)], &
                                [2, placed%n_surface])
    placed%surface_force_n = reshape([placed%surface_force_n, 0.0_dp, -magnitude_n], [2, placed%n_surface])
    placed%surface_spread_x_m = reshape([placed%surface_spread_x_m, x_lo, x_hi], [2, placed%n_surface])
    placed%surface_patch_m = [placed%surface_patch_m, patch_m]
    placed%surface_first = [placed%surface_first, placed%n + 1]
    placed%surface_strips = [placed%surface_strips, merge(1, dispersion_strips, x_hi - x_lo <= boundary_tol_m)]
    placed%surface_retained = [placed%surface_retained, 1.0_dp]
    if (x_hi - x_lo <= boundary_tol_m) then
      call add_load(placed, blk, j, [x0, y0], [0.0_dp, -magnitude_n], .true., kind)
      return
    end if
    dx = (x_hi - x_lo)/dispersion_strips
    do k = 1, dispersion_strips
      xs = x_lo + (k - 0.5_dp)*dx
      call top_surface(asm, xs, ys, blk, ok)
      if (.not. ok) then   ! (the spread ends lie on the blocks, and a bridge's top has no gap)
        call fail(status, '&load live point load '//itoa(j)//trim(axle_words(a))//' spreads over x = '// &
                  fmt_significant(xs, 6)//' m, where no block stands')
        return
      end if
      call add_load(placed, blk, j, [xs, ys], [0.0_dp, -magnitude_n/dispersion_strips], .true., kind)
    end do
  end subroutine disperse_load

  !> Live load j (axle a) of `magnitude_n`, a patch of `patch_m` centred on `x0` (0: a
  !> point), on the fill's surface of `asm`, spread by Flamant's vertical stress onto the
  !> blocks' top: the spread's ends are the outermost x of the deck where that stress, at
  !> the fill's depth over the top there, is at least boussinesq_cutoff x the stress beneath
  !> the load (bisection between samples of deck_samples), or the deck's ends; between them
  !> the strips of `strip_edges`, each carrying the closed-form integral of the stress over
  !> its length at the depth at its middle, at its middle on the block on top there, all
  !> scaled so that they sum to the load.
  subroutine boussinesq_load(asm, placed, j, a, x0, magnitude_n, patch_m, status)
    type(assembly_t), intent(in) :: asm
    type(placed_loads_t), intent(inout) :: placed
    integer, intent(in) :: j, a
    real(dp), intent(in) :: x0, magnitude_n, patch_m
    type(status_t), intent(inout) :: status
    real(dp) :: deck(2), ends(2), y0, z0, sigma_ref, x, dx, xs, ys, lo, hi
    real(dp), allocatable :: edges(:), f(:)
    integer, allocatable :: blk(:)
    integer :: b, k, n, side, inner, step
    logical :: ok
    call top_surface(asm, x0, y0, b, ok)
    z0 = asm%fill_level_m - y0
    if (.not. z0 > boundary_tol_m) then
      call fail(status, '&load live point load '//itoa(j)//trim(axle_words(a))//' at x = '//fmt_significant(x0, 6)// &
                ' m stands where the fill has no depth over the blocks (y = '//fmt_significant(y0, 6)// &
                ' m): Boussinesq''s spread needs fill beneath the load')
      return
    end if
    sigma_ref = flamant_pressure(magnitude_n, patch_m, 0.0_dp, z0)
    deck = [huge(1.0_dp), -huge(1.0_dp)]
    do b = 1, asm%n_bodies
      deck(1) = min(deck(1), minval(asm%polygon(b)%xy(1, :)))
      deck(2) = max(deck(2), maxval(asm%polygon(b)%xy(1, :)))
    end do
    dx = (deck(2) - deck(1))/deck_samples
    do side = 1, 2
      ! From the deck's end towards the load: the first sample at or above the cutoff.
      step = merge(1, -1, side == 1)
      inner = merge(0, deck_samples, side == 1)
      do while (above_cutoff(asm, deck(1) + inner*dx, x0, magnitude_n, patch_m, sigma_ref) < 0.0_dp)
        inner = inner + step
      end do
      ends(side) = deck(1) + inner*dx
      if (inner == merge(0, deck_samples, side == 1)) cycle     ! truncated at the deck's end
      lo = ends(side) - step*dx        ! below the cutoff
      hi = ends(side)                  ! at or above it
      do k = 1, 60
        x = 0.5_dp*(lo + hi)
        if (above_cutoff(asm, x, x0, magnitude_n, patch_m, sigma_ref) < 0.0_dp) then
          lo = x
        else
          hi = x
        end if
      end do
      ends(side) = 0.5_dp*(lo + hi)
    end do
    edges = strip_edges(asm, ends)
    n = size(edges) - 1
    allocate (f(n), blk(n))
    do k = 1, n
      xs = 0.5_dp*(edges(k) + edges(k + 1))
      call top_surface(asm, xs, ys, blk(k), ok)
      if (.not. ok) then   ! (a bridge's top has no gap)
        call fail(status, '&load live point load '//itoa(j)//trim(axle_words(a))//' spreads over x = '// &
                  fmt_significant(xs, 6)//' m, where no block stands')
        return
      end if
      f(k) = flamant_force(magnitude_n, patch_m, edges(k) - x0, edges(k + 1) - x0, asm%fill_level_m - ys)
    end do
    placed%n_surface = placed%n_surface + 1
    placed%surface_source = [placed%surface_source, j]
    placed%surface_xy = reshape([placed%surface_xy, x0, asm%fill_level_m], [2, placed%n_surface])
    placed%surface_force_n = reshape([placed%surface_force_n, 0.0_dp, -magnitude_n], [2, placed%n_surface])
    placed%surface_spread_x_m = reshape([placed%surface_spread_x_m, ends], [2, placed%n_surface])
    placed%surface_patch_m = [placed%surface_patch_m, patch_m]
    placed%surface_first = [placed%surface_first, placed%n + 1]
    placed%surface_strips = [placed%surface_strips, n]
    placed%surface_retained = [placed%surface_retained, sum(f)/magnitude_n]
    placed%surface_edges_x_m = [placed%surface_edges_x_m, edges]
    f = f*(magnitude_n/sum(f))
    do k = 1, n
      xs = 0.5_dp*(edges(k) + edges(k + 1))
      call top_surface(asm, xs, ys, b, ok)   ! (found above)
      call add_load(placed, blk(k), j, [xs, ys], [0.0_dp, -f(k)], .true., kind_dispersed)
    end do

  end subroutine boussinesq_load

  !> The ends of the strips from ends(1) to ends(2): dispersion_strips of equal length,
  !> cut again at every vertex of a block between them, so that each strip lies on one
  !> straight face of the top (a strip across a joint would put its whole load on one side).
  pure function strip_edges(asm, ends) result(edges)
    type(assembly_t), intent(in) :: asm
    real(dp), intent(in) :: ends(2)
    real(dp), allocatable :: edges(:), cuts(:)
    integer, allocatable :: order(:)
    integer :: b, k
    cuts = [(ends(1) + k*(ends(2) - ends(1))/dispersion_strips, k=0, dispersion_strips)]
    cuts(dispersion_strips + 1) = ends(2)
    do b = 1, asm%n_bodies
      do k = 1, size(asm%polygon(b)%xy, 2)
        associate (x => asm%polygon(b)%xy(1, k))
          if (x > ends(1) + boundary_tol_m .and. x < ends(2) - boundary_tol_m) cuts = [cuts, x]
        end associate
      end do
    end do
    order = stable_order(reshape(cuts, [1, size(cuts)]))
    edges = [cuts(order(1))]
    do k = 2, size(order)
      if (cuts(order(k)) - edges(size(edges)) > boundary_tol_m) edges = [edges, cuts(order(k))]
    end do
    edges(size(edges)) = ends(2)
  end function strip_edges

  !> Flamant's stress of a load `load_n` over `patch_m` centred on `x0` at the fill's depth
  !> over the top of `asm` at `x`, over `sigma_ref` (the stress beneath the load), less
  !> boussinesq_cutoff: >= 0 within the spread.
  pure real(dp) function above_cutoff(asm, x, x0, load_n, patch_m, sigma_ref) result(excess)
    type(assembly_t), intent(in) :: asm
    real(dp), intent(in) :: x, x0, load_n, patch_m, sigma_ref
    real(dp) :: y
    integer :: top
    logical :: found
    call top_surface(asm, x, y, top, found)
    excess = flamant_pressure(load_n, patch_m, x - x0, asm%fill_level_m - y)/sigma_ref - boussinesq_cutoff
  end function above_cutoff

  !> ' (a patch of p m)', or '' for a point.
  function patch_words(patch_m) result(text)
    real(dp), intent(in) :: patch_m
    character(len=:), allocatable :: text
    text = ''
    if (patch_m > 0.0_dp) text = ' (a patch of '//fmt_significant(patch_m, 6)//' m)'
  end function patch_words

  !> The fill's weight over every top face of a free block of `asm` that is the top
  !> surface there: the trapezoid between the face and the fill's level, its weight at its
  !> centroid's x on the face (a vertical force: its moment depends on that x alone). Faces
  !> of driven blocks carry theirs to the supports and are left out.
  pure subroutine add_fill_weight(asm, placed)
    type(assembly_t), intent(in) :: asm
    type(placed_loads_t), intent(inout) :: placed
    real(dp) :: p0(2), p1(2), h0, h1, xc, weight
    integer :: blk, k
    logical :: carries
    do blk = 1, asm%n_bodies
      if (asm%driven(blk)) cycle
      do k = 1, size(asm%polygon(blk)%xy, 2)
        call fill_face(asm, blk, k, p0, p1, carries)
        if (.not. carries) cycle
        ! From p1 (left, height h0 under the level) to p0 (right, h1).
        h0 = asm%fill_level_m - p1(2)
        h1 = asm%fill_level_m - p0(2)
        weight = asm%fill_weight_n_m2*(p0(1) - p1(1))*0.5_dp*(h0 + h1)
        if (weight <= 0.0_dp) cycle
        xc = p1(1) + (p0(1) - p1(1))*(h0 + 2.0_dp*h1)/(3.0_dp*(h0 + h1))
        call add_load(placed, blk, 0, [xc, p1(2) + (xc - p1(1))*(p0(2) - p1(2))/(p0(1) - p1(1))], [0.0_dp, -weight], &
                      .false., kind_fill)
      end do
    end do
  end subroutine add_fill_weight

  !> Whether face k of block `blk` (from vertex k, `p0`, to the next, `p1`) `carries` fill: a
  !> face that runs right to left (a top face of a counter-clockwise polygon) and is the
  !> top surface of the assembly at its midpoint.
  pure subroutine fill_face(asm, blk, k, p0, p1, carries)
    type(assembly_t), intent(in) :: asm
    integer, intent(in) :: blk, k
    real(dp), intent(out) :: p0(2), p1(2)
    logical, intent(out) :: carries
    real(dp) :: xm, ym, yt
    integer :: nv, top
    logical :: ok
    nv = size(asm%polygon(blk)%xy, 2)
    p0 = asm%polygon(blk)%xy(:, k)
    p1 = asm%polygon(blk)%xy(:, modulo(k, nv) + 1)
    carries = .false.
    if (p1(1) - p0(1) >= -boundary_tol_m) return
    xm = 0.5_dp*(p0(1) + p1(1))
    ym = 0.5_dp*(p0(2) + p1(2))
    call top_surface(asm, xm, yt, top, ok)
    carries = ok .and. top == blk .and. abs(yt - ym) <= 1.0e-9_dp*max(1.0_dp, abs(ym))
  end subroutine fill_face

  !> The fill a free block `blk` carries, as a body: the columns between its top faces and
  !> the fill's level (the columns whose weight `add_fill_weight` places), their area
  !> [m2], centroid [m] and polar second moment of area about that centroid [m4]; all 0
  !> without a fill or a top face. The dynamics add it to the block's mass and inertia.
  pure subroutine fill_column(asm, blk, area_m2, centroid_xy, polar_m4)
    type(assembly_t), intent(in) :: asm
    integer, intent(in) :: blk
    real(dp), intent(out) :: area_m2, centroid_xy(2), polar_m4
    real(dp) :: p0(2), p1(2), column(2, 4), a, c(2), first(2), second
    integer :: k
    logical :: carries
    area_m2 = 0.0_dp
    first = 0.0_dp
    second = 0.0_dp
    centroid_xy = 0.0_dp
    polar_m4 = 0.0_dp
    if (.not. asm%has_fill .or. asm%driven(blk)) return
    do k = 1, size(asm%polygon(blk)%xy, 2)
      call fill_face(asm, blk, k, p0, p1, carries)
      if (.not. carries) cycle
      ! Counter-clockwise: along the face left to right, then up to the level and back.
      column = reshape([p1, p0, [p0(1), asm%fill_level_m], [p1(1), asm%fill_level_m]], [2, 4])
      a = polygon_area(column)
      if (.not. a > 0.0_dp) cycle           ! a face at the level carries no fill
      c = polygon_centroid(column)
      area_m2 = area_m2 + a
      first = first + a*c
      ! Each column's polar moment about the origin (parallel axes), to move to the whole's centroid.
      second = second + polygon_polar_moment(column) + a*dot_product(c, c)
    end do
    if (area_m2 <= 0.0_dp) return
    centroid_xy = first/area_m2
    polar_m4 = second - area_m2*dot_product(centroid_xy, centroid_xy)
  end subroutine fill_column

  !> The fill's horizontal pressure on every top face of a free block that is the top
  !> surface there: k times the vertical stress (weight per unit area x depth) on the face's
  !> vertical projection from y_a to y_b, a resultant k w_f ((F - y_a)^2 - (F - y_b)^2)/2 at
  !> the height of that triangle-trapezoid's centroid, horizontal and into the block; k
  !> between the active and the mobilised passive coefficient (the LP chooses).
  pure subroutine add_fill_pressure(asm, placed)
    type(assembly_t), intent(in) :: asm
    type(placed_loads_t), intent(inout) :: placed
    real(dp) :: p0(2), p1(2), ya, yb, yt, resultant, yc, t, f
    integer :: blk, k, nv, top
    logical :: ok
    f = asm%fill_level_m
    do blk = 1, asm%n_bodies
      if (asm%driven(blk)) cycle
      nv = size(asm%polygon(blk)%xy, 2)
      do k = 1, nv
        p0 = asm%polygon(blk)%xy(:, k)
        p1 = asm%polygon(blk)%xy(:, modulo(k, nv) + 1)
        if (p1(1) - p0(1) >= -boundary_tol_m) cycle      ! a top face runs right to left
        call top_surface(asm, 0.5_dp*(p0(1) + p1(1)), yt, top, ok)
        if (.not. ok .or. top /= blk .or. abs(yt - 0.5_dp*(p0(2) + p1(2))) > 1.0e-9_dp*max(1.0_dp, abs(yt))) cycle
        ya = min(p0(2), p1(2))
        yb = max(p0(2), p1(2))
        if (yb - ya <= boundary_tol_m) cycle               ! a level face: no horizontal pressure
        resultant = asm%fill_weight_n_m2*((f - ya)**2 - (f - yb)**2)/2.0_dp
        ! The centroid of the pressure (f - y) over [ya, yb].
        yc = ((f*(yb**2 - ya**2)/2.0_dp) - (yb**3 - ya**3)/3.0_dp)/((f - ya)**2/2.0_dp - (f - yb)**2/2.0_dp)
        t = (yc - p0(2))/(p1(2) - p0(2))
        placed%n_pressure = placed%n_pressure + 1
        placed%pressure_block = [placed%pressure_block, blk]
        placed%pressure_xy = reshape([placed%pressure_xy, p0 + t*(p1 - p0)], [2, placed%n_pressure])
        ! Into the block: the face's outward normal (p1 - p0 turned -90 deg) has the x of p1(2) - p0(2).
        placed%pressure_dir = reshape([placed%pressure_dir, -sign(1.0_dp, p1(2) - p0(2)), 0.0_dp], &
                                      [2, placed%n_pressure])
        placed%pressure_lo_n = [placed%pressure_lo_n, asm%fill_active_k*resultant]
        placed%pressure_hi_n = [placed%pressure_hi_n, asm%fill_passive_k*resultant]
      end do
    end do
  end subroutine add_fill_pressure

  !> Where the line from (x0, the fill's level) down at the dispersion angle towards
  !> `side` (-1 left, +1 right) meets the top surface of the blocks [m] (the top surface
  !> of a bridge runs unbroken from one abutment's end to the other's); -huge or huge when
  !> the line leaves the assembly above it. Bisection on the line's height over the surface.
  pure function spread_end(asm, x0, side) result(x)
    type(assembly_t), intent(in) :: asm
    real(dp), intent(in) :: x0, side
    real(dp) :: x, lo, hi, y, slope, lowest, x_end
    integer :: blk, k
    logical :: ok
    real(dp), parameter :: pi = acos(-1.0_dp)
    x = x0
    if (asm%dispersion_angle_deg == 0.0_dp) return
    slope = tan(asm%dispersion_angle_deg*pi/180.0_dp)   ! horizontal run per unit of depth
    lowest = huge(1.0_dp)
    x_end = merge(huge(1.0_dp), -huge(1.0_dp), side < 0.0_dp)
    do k = 1, asm%n_bodies
      lowest = min(lowest, minval(asm%polygon(k)%xy(2, :)))
      if (side < 0.0_dp) x_end = min(x_end, minval(asm%polygon(k)%xy(1, :)))
      if (side > 0.0_dp) x_end = max(x_end, maxval(asm%polygon(k)%xy(1, :)))
    end do
    ! Beyond this the line is below every block: it has met the top surface by then.
    hi = x0 + side*slope*(asm%fill_level_m - lowest)
    if (side*(hi - x_end) > 0.0_dp) then
      call top_surface(asm, x_end, y, blk, ok)
      if (asm%fill_level_m - abs(x_end - x0)/slope > y) then
        x = merge(-huge(1.0_dp), huge(1.0_dp), side < 0.0_dp)
        return
      end if
      hi = x_end
    end if
    lo = x0
    do k = 1, 100
      x = 0.5_dp*(lo + hi)
      call top_surface(asm, x, y, blk, ok)
      if (asm%fill_level_m - abs(x - x0)/slope > y) then
        lo = x
      else
        hi = x
      end if
    end do
    x = 0.5_dp*(lo + hi)
  end function spread_end

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

end module voussoir_placed_loads
