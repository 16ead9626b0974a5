!> Tests of the loads of &load in the limit analysis by linear programming
!> (voussoir_placed_loads, voussoir_limit_lp's point loads): closed forms derived by hand
!> for a block and a stack on a fixed base under point loads, the placement of loads on
!> the blocks (containment, the top surface), and the refusals.
!>
!> Derivations (a block b wide, h high, weight W, on a fixed base wider than it, its
!> corners (0,0), (b,0), (b,h), (0,h); a live point load lambda P towards +x at (0,h)):
!> - tipping about the base corner (b,0): the load's moment about it is lambda P h, the
!>   weight's restoring moment W b/2, so lambda = W b / (2 P h);
!> - sliding on the base: lambda P = mu W, so lambda = mu W / P; the least of the two
!>   governs (friction high: tipping; low: sliding);
!> - a dead vertical load Q on the top at the centroid's x (b/2, h): it adds Q b/2 to the
!>   restoring moment and Q to the normal force, lambda = (W + Q) b / (2 P h);
!> - a dead Q at the top corner (0,h), the far side from the pivot: it restores with the
!>   lever b, lambda = (W b/2 + Q b) / (P h);
!> - two equal blocks stacked, the live load at (0, h/2) on the lower one's face: the
!>   upper block gets no load and rides on the lower, which tips about (b,0) with it:
!>   lambda P h/2 = 2 W b/2, lambda = 2 W b / (P h) (friction high);
!> - a distributed dead load q over the whole top: Q = q b at b/2, as the dead point load;
!>   over the half away from the pivot (x from 0 to b/2): Q = q b/2 at b/4, lever 3b/4 about
!>   the pivot, lambda = (W b/2 + 3 q b^2/8) / (P h);
!> - an axle group: P at (0.05, h) repeated at +0.1 m, both on the top (y = h): 2 P at
!>   height h, lambda = W b / (4 P h).
!> - a live patch P of length p centred on x0 on the top surface: uniform, so its strips
!>   sum to P and their resultant stands at x0; each strip lies within x0 -/+ p/2 on the
!>   block the top surface has there; on a single block its moment about any point is
!>   that of the point load P at x0.
!> - Flamant's stress (voussoir_flamant): its closed-form integral over an interval against
!>   Simpson's rule on the stress itself, over the whole line P; a patch's stress on its
!>   centre line and under its edge against the strip load's textbook form
!>   (q/pi)(alpha + sin(alpha) cos(alpha + 2 delta)), alpha the angle the patch subtends,
!>   delta that of its near edge from the vertical (-alpha/2 on the centre line, 0 under an
!>   edge); a patch much shorter than the depth against the point.
program test_limit_loads
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t
  use voussoir_assembly, only: assembly_t, build_arch, role_voussoir, role_foundation
  use voussoir_wall, only: box, block_stack
  use voussoir_load_config, only: load_config_t
  use voussoir_placed_loads, only: placed_loads_t, place_loads, block_at, top_surface, kind_patch, dispersion_strips
  use voussoir_block_interfaces, only: interface_set_t, find_interfaces
  use voussoir_limit_lp, only: block_loads_t, lp_result_t, block_loads, add_placed_loads, lp_capacity, &
                               joint_hinge, joint_sliding
  use voussoir_assert, only: assert_true, assert_close, assert_summary
  use voussoir_flamant, only: flamant_pressure, flamant_force
  implicit none

  real(dp), parameter :: b = 0.2_dp, h = 0.5_dp, rho = 700.0_dp, width = 0.145_dp, g = 9.81_dp
  real(dp), parameter :: w_n = rho*b*h*width*g   !! the weight of one block [N]

  call test_tipping_and_sliding()
  call test_dead_loads()
  call test_two_block_stack()
  call test_distributed_and_axles()
  call test_placement()
  call test_refusals()
  call test_patch()
  call test_flamant()
  call assert_summary()

contains

  !> The associative load factor of `asm` under the loads of `d` with friction mu.
  subroutine capacity(asm, d, mu, res, status)
    type(assembly_t), intent(in) :: asm
    type(load_config_t), intent(in) :: d
    real(dp), intent(in) :: mu
    type(lp_result_t), intent(out) :: res
    type(status_t), intent(inout) :: status
    type(interface_set_t) :: faces
    type(block_loads_t) :: loads
    type(placed_loads_t) :: placed
    real(dp), allocatable :: friction(:)
    call find_interfaces(asm, 1.0e-9_dp, 0.0_dp, faces, status)
    if (status%ok) call place_loads(d, asm, 0.0_dp, placed, status)
    if (.not. status%ok) return
    call block_loads(asm, rho, width, g, loads)
    call add_placed_loads(placed, loads)
    allocate (friction(faces%n))
    friction = mu
    call lp_capacity(asm, faces, loads, friction, 0.0_dp*friction, res, status)
  end subroutine capacity

  !> One point load: magnitude [N], direction [deg], point [m], live or dead.
  subroutine add_load(d, p_n, dir_deg, x_m, y_m, live)
    type(load_config_t), intent(inout) :: d
    real(dp), intent(in) :: p_n, dir_deg, x_m, y_m
    logical, intent(in) :: live
    d%n_point_loads = d%n_point_loads + 1
    d%point_load_n(d%n_point_loads) = p_n
    d%point_load_dir_deg(d%n_point_loads) = dir_deg
    d%point_load_x_m(d%n_point_loads) = x_m
    d%point_load_y_m(d%n_point_loads) = y_m
    d%point_load_live(d%n_point_loads) = live
  end subroutine add_load

  !> P = 100 N at the top corner (0,h) towards +x: tips at W b/(2 P h) = 0.2 W/P with
  !> mu = 0.8; slides at mu W / P with mu = 0.1.
  subroutine test_tipping_and_sliding()
    type(assembly_t) :: asm
    type(load_config_t) :: d
    type(lp_result_t) :: res
    type(status_t) :: status
    real(dp), parameter :: p = 100.0_dp
    call block_stack(b, h, 1, asm)
    call add_load(d, p, 0.0_dp, 0.0_dp, h, .true.)
    call capacity(asm, d, 0.8_dp, res, status)
    call assert_true(status%ok, 'point load, friction 0.8: solved')
    call assert_close(res%load_factor, w_n*b/(2*p*h), 'point load at the top corner: tips at W b / (2 P h)', &
                      rtol=1.0e-9_dp)
    call assert_close(res%load_factor_upper, res%load_factor, 'tipping: upper bound (work) = lower bound', &
                      rtol=1.0e-9_dp)
    call assert_true(res%mode(1) == joint_hinge, 'tipping: the base joint hinges')
    status = status_t()
    call capacity(asm, d, 0.1_dp, res, status)
    call assert_true(status%ok, 'point load, friction 0.1: solved')
    call assert_close(res%load_factor, 0.1_dp*w_n/p, 'point load, low friction: slides at mu W / P', rtol=1.0e-9_dp)
    call assert_true(res%mode(1) == joint_sliding, 'low friction: the base joint slides')
    ! Pushing at mid-height doubles the tipping load factor: W b / (P h).
    d%point_load_y_m(1) = 0.5_dp*h
    status = status_t()
    call capacity(asm, d, 0.8_dp, res, status)
    call assert_close(res%load_factor, w_n*b/(p*h), 'point load at mid-height: tips at W b / (P h)', rtol=1.0e-9_dp)
  end subroutine test_tipping_and_sliding

  !> A dead vertical Q = 50 N on the top: at the centroid's x, (W + Q) b / (2 P h); at the
  !> corner away from the pivot, (W b/2 + Q b) / (P h); over the pivot, no change.
  subroutine test_dead_loads()
    type(assembly_t) :: asm
    type(load_config_t) :: d
    type(lp_result_t) :: res
    type(status_t) :: status
    real(dp), parameter :: p = 100.0_dp, q = 50.0_dp
    call block_stack(b, h, 1, asm)
    call add_load(d, p, 0.0_dp, 0.0_dp, h, .true.)
    call add_load(d, q, -90.0_dp, 0.5_dp*b, h, .false.)
    call capacity(asm, d, 0.8_dp, res, status)
    call assert_true(status%ok, 'dead load at the centroid x: solved')
    call assert_close(res%load_factor, (w_n + q)*b/(2*p*h), 'dead Q on top at the centroid x: (W + Q) b / (2 P h)', &
                      rtol=1.0e-9_dp)
    call assert_close(res%load_factor_upper, res%load_factor, 'dead Q: upper bound (work) = lower bound', &
                      rtol=1.0e-9_dp)
    d%point_load_x_m(2) = 0.0_dp
    call capacity(asm, d, 0.8_dp, res, status)
    call assert_close(res%load_factor, (0.5_dp*w_n*b + q*b)/(p*h), 'dead Q at the far corner: (W b/2 + Q b) / (P h)', &
                      rtol=1.0e-9_dp)
    d%point_load_x_m(2) = b
    call capacity(asm, d, 0.8_dp, res, status)
    call assert_close(res%load_factor, w_n*b/(2*p*h), 'dead Q over the pivot: W b / (2 P h) unchanged', rtol=1.0e-9_dp)
    ! Sliding with the dead load: mu (W + Q) / P.
    d%point_load_x_m(2) = 0.5_dp*b
    call capacity(asm, d, 0.1_dp, res, status)
    call assert_close(res%load_factor, 0.1_dp*(w_n + q)/p, 'dead Q, low friction: slides at mu (W + Q) / P', &
                      rtol=1.0e-9_dp)
  end subroutine test_dead_loads

  !> Two blocks; P at (0, h/2) on the lower block: the stack tips at 2 W b / (P h).
  subroutine test_two_block_stack()
    type(assembly_t) :: asm
    type(load_config_t) :: d
    type(lp_result_t) :: res
    type(status_t) :: status
    real(dp), parameter :: p = 100.0_dp
    call block_stack(b, h, 2, asm)
    call add_load(d, p, 0.0_dp, 0.0_dp, 0.5_dp*h, .true.)
    call capacity(asm, d, 0.8_dp, res, status)
    call assert_true(status%ok, 'stack: solved')
    call assert_close(res%load_factor, 2*w_n*b/(p*h), 'two-block stack, load on the lower block: 2 W b / (P h)', &
                      rtol=1.0e-9_dp)
    ! The same load on the upper block's top corner: the upper block tips about (b, h),
    ! lambda P h = W b/2, as does the whole stack (lambda P 2h = 2 W b/2): W b / (2 P h).
    d%point_load_y_m(1) = 2*h
    call capacity(asm, d, 0.8_dp, res, status)
    call assert_close(res%load_factor, w_n*b/(2*p*h), 'two-block stack, load on top: W b / (2 P h)', rtol=1.0e-9_dp)
  end subroutine test_two_block_stack

  !> The distributed dead load's strips and an axle group on the top of the block.
  subroutine test_distributed_and_axles()
    type(assembly_t) :: asm
    type(load_config_t) :: d
    type(lp_result_t) :: res
    type(status_t) :: status
    real(dp), parameter :: p = 100.0_dp, q = 1000.0_dp
    call block_stack(b, h, 1, asm)
    call add_load(d, p, 0.0_dp, 0.0_dp, h, .true.)
    d%dead_load_n_per_m = q
    d%dead_load_x0_m = 0.0_dp
    d%dead_load_x1_m = b
    call capacity(asm, d, 0.8_dp, res, status)
    call assert_true(status%ok, 'distributed dead load: solved')
    call assert_close(res%load_factor, (w_n + q*b)*b/(2*p*h), 'distributed q over the top: (W + q b) b / (2 P h)', &
                      rtol=1.0e-9_dp)
    d%dead_load_x1_m = 0.5_dp*b
    call capacity(asm, d, 0.8_dp, res, status)
    call assert_close(res%load_factor, (0.5_dp*w_n*b + 3*q*b**2/8)/(p*h), &
                      'distributed q over the far half: (W b/2 + 3 q b^2/8) / (P h)', rtol=1.0e-9_dp)
    d = load_config_t()
    call add_load(d, p, 0.0_dp, 0.05_dp, 0.3_dp, .true.)   ! y: placed on the top surface instead
    d%n_axles = 1
    d%axle_spacing_m(1) = 0.1_dp
    call capacity(asm, d, 0.8_dp, res, status)
    call assert_true(status%ok, 'axle group: solved')
    call assert_close(res%load_factor, w_n*b/(4*p*h), 'axle group of two P on the top: W b / (4 P h)', rtol=1.0e-9_dp)
  end subroutine test_distributed_and_axles

  !> Containment with 1e-9 m of tolerance; the top surface of a stack and of an arch.
  subroutine test_placement()
    type(assembly_t) :: asm
    real(dp) :: y
    integer :: blk
    logical :: found
    call block_stack(b, h, 2, asm)
    call assert_true(block_at(asm, [0.1_dp, 0.25_dp]) == 2, 'a point inside the lower block')
    call assert_true(block_at(asm, [0.1_dp, 0.75_dp]) == 3, 'a point inside the upper block')
    call assert_true(block_at(asm, [b + 0.5e-9_dp, 0.25_dp]) == 2, 'a point 0.5e-9 m outside a face: on it')
    call assert_true(block_at(asm, [b + 2.0e-9_dp, 0.75_dp]) == 0, 'a point 2e-9 m outside every block: none')
    call assert_true(block_at(asm, [0.3_dp, -0.1_dp]) == 1, 'a point in the driven base')
    call top_surface(asm, 0.05_dp, y, blk, found)
    call assert_true(found .and. blk == 3, 'top surface over the stack: the upper block')
    call assert_close(y, 2*h, 'top surface over the stack at 2 h', rtol=1.0e-12_dp)
    call top_surface(asm, 0.3_dp, y, blk, found)
    call assert_true(found .and. blk == 1 .and. abs(y) < 1.0e-12_dp, 'top surface beside the stack: the base')
    call top_surface(asm, 5.0_dp, y, blk, found)
    call assert_true(.not. found, 'top surface beyond the assembly: none')
    ! A semicircular arch of 10 voussoirs, R_ext = 1, centred at the origin: joint j at
    ! 180 - 18 j degrees from +x; the top is the extrados corner R_ext (cos, sin) there.
    call build_arch(180.0_dp, 10, 1.0_dp, 0.1_dp, asm)
    call top_surface(asm, 0.0_dp, y, blk, found)
    call assert_close(y, 1.0_dp, 'arch: top surface at the crown = R_ext', rtol=1.0e-12_dp)
    call top_surface(asm, cos(acos(-1.0_dp)*0.4_dp), y, blk, found)
    call assert_close(y, sin(acos(-1.0_dp)*0.4_dp), 'arch: top surface at an extrados corner (72 deg)', &
                      rtol=1.0e-12_dp)
  end subroutine test_placement

  !> A load outside every block is refused by number and point; a dead load that the
  !> block cannot carry (far beyond its base) is infeasible: "the dead load alone".
  subroutine test_refusals()
    type(assembly_t) :: asm
    type(load_config_t) :: d
    type(lp_result_t) :: res
    type(status_t) :: status
    call block_stack(b, h, 1, asm)
    call add_load(d, 100.0_dp, 0.0_dp, 0.0_dp, h, .true.)
    call add_load(d, 100.0_dp, 0.0_dp, 3.0_dp, 4.0_dp, .true.)
    call capacity(asm, d, 0.8_dp, res, status)
    call assert_true(.not. status%ok .and. index(status%message, '&load point load 2 at (x, y) = (3, 4) m lies in no '// &
                     'block') > 0, 'a load outside every block: refused, named ('//trim(status%message)//')')
    ! A dead horizontal 0.9 W low on a block with mu = 0.8 (below its tipping moment
    ! 0.9 W x 0.1 m = 0.09 W m < W b/2 = 0.1 W m): it slides under the dead load alone.
    d = load_config_t()
    call add_load(d, 100.0_dp, 0.0_dp, 0.0_dp, h, .true.)
    call add_load(d, 0.9_dp*w_n, 0.0_dp, 0.0_dp, 0.1_dp, .false.)
    status = status_t()
    call capacity(asm, d, 0.8_dp, res, status)
    call assert_true(.not. status%ok .and. index(status%message, 'dead load alone brings the assembly down') > 0, &
                     'dead load beyond friction: infeasible, said so')
    ! A live load pressing the block down on its base opens no mechanism: unbounded, the block named.
    d = load_config_t()
    call add_load(d, 100.0_dp, -90.0_dp, 0.5_dp*b, h, .true.)
    status = status_t()
    call capacity(asm, d, 0.8_dp, res, status)
    call assert_true(.not. status%ok .and. index(status%message, 'unbounded') > 0 .and. &
                     index(status%message, 'block 2') > 0, 'a live load pressing down: unbounded, block 2 named ('// &
                     trim(status%message)//')')
  end subroutine test_refusals

  !> A live patch of 0.7 m centred at x0 = -0.2 m on the extrados of a semicircular arch
  !> (R_ext 1 m, 10 voussoirs): its strips sum to P, their resultant at x0, each within the
  !> patch on the block on top there (several voussoirs); the patch in words of the JSON
  !> (n_surface, spread = x0 -/+ p/2). A patch on a block alone gives the point load's
  !> force and moment on it. Refusals: a patch beyond the assembly; a patch of a load
  !> acting at its own point (no path, no axles, no fill).
  subroutine test_patch()
    type(assembly_t) :: asm
    type(load_config_t) :: d
    type(placed_loads_t) :: placed, point
    type(block_loads_t) :: patch_loads, point_loads
    type(status_t) :: status
    real(dp), parameter :: p = 1000.0_dp, x0 = -0.2_dp, length = 0.7_dp
    real(dp) :: total, moment, y
    integer :: k, blk, n_strips, blocks_hit(20)
    logical :: found, on_top
    call build_arch(180.0_dp, 10, 1.0_dp, 0.1_dp, asm)
    call add_load(d, p, -90.0_dp, x0, 0.0_dp, .true.)
    d%point_load_patch_m(1) = length
    d%path_points = 2          ! the live loads stand on the top surface
    d%path_x0_m = -0.5_dp
    d%path_x1_m = 0.5_dp
    call place_loads(d, asm, 0.0_dp, placed, status)
    call assert_true(status%ok, 'patch on an arch: placed')
    total = 0.0_dp
    moment = 0.0_dp
    n_strips = 0
    on_top = .true.
    blocks_hit = 0
    do k = 1, placed%n
      if (placed%kind(k) /= kind_patch) cycle
      n_strips = n_strips + 1
      total = total - placed%force_n(2, k)
      moment = moment - placed%force_n(2, k)*placed%xy(1, k)
      call top_surface(asm, placed%xy(1, k), y, blk, found)
      on_top = on_top .and. found .and. blk == placed%block(k) .and. abs(y - placed%xy(2, k)) < 1.0e-12_dp .and. &
               abs(placed%xy(1, k) - x0) < 0.5_dp*length .and. placed%live(k) .and. placed%force_n(1, k) == 0.0_dp
      blocks_hit(placed%block(k)) = 1
    end do
    call assert_true(n_strips == dispersion_strips, 'patch: '//'its strips placed')
    call assert_close(total, p, 'patch: the strips sum to the load', rtol=1.0e-12_dp)
    call assert_close(moment/total, x0, 'patch: the strips'' resultant at the patch''s centre', atol=1.0e-12_dp)
    call assert_true(on_top, 'patch: every strip within x0 -/+ p/2 on the block on top there, live, vertical')
    call assert_true(sum(blocks_hit) >= 3, 'patch: it covers several voussoirs')
    call assert_true(placed%n_surface == 1 .and. .not. placed%surface_on_fill, 'patch: recorded once, not on a fill')
    call assert_close(placed%surface_spread_x_m(1, 1), x0 - 0.5_dp*length, 'patch: from x0 - p/2', atol=1.0e-12_dp)
    call assert_close(placed%surface_spread_x_m(2, 1), x0 + 0.5_dp*length, 'patch: to x0 + p/2', atol=1.0e-12_dp)
    ! On one block (the voussoir right of the crown joint spans x = 0 .. cos 72 deg = 0.309 m
    ! at its extrados corners), a patch of 0.2 m at x = 0.15 m loads it as the point load
    ! there (force and moment).
    d%point_load_x_m(1) = 0.15_dp
    d%point_load_patch_m(1) = 0.2_dp
    call place_loads(d, asm, 0.0_dp, placed, status)
    d%point_load_patch_m(1) = 0.0_dp
    call place_loads(d, asm, 0.0_dp, point, status)
    call block_loads(asm, rho, width, g, patch_loads)
    call block_loads(asm, rho, width, g, point_loads)
    call add_placed_loads(placed, patch_loads)
    call add_placed_loads(point, point_loads)
    call assert_true(status%ok .and. maxval(abs(patch_loads%live_n - point_loads%live_n)) < 1.0e-9_dp*p .and. &
                     maxval(abs(patch_loads%live_moment_nm - point_loads%live_moment_nm)) < 1.0e-12_dp*p, &
                     'a patch on one block = the point load at its centre (force and moment)')
    ! Beyond the arch's end (x = 1 m): refused, the patch named.
    d%point_load_x_m(1) = 0.9_dp
    d%point_load_patch_m(1) = 0.4_dp
    call place_loads(d, asm, 0.0_dp, placed, status)
    call assert_true(.not. status%ok .and. index(status%message, 'a patch of 0.4 m') > 0 .and. &
                     index(status%message, 'stands over no block') > 0, 'a patch beyond the arch: refused ('// &
                     trim(status%message)//')')
    ! A load at its own point (no path, no axles, no fill) cannot be a patch.
    status = status_t()
    d%point_load_x_m(1) = 0.0_dp
    d%point_load_y_m(1) = 0.95_dp
    d%path_points = 0
    call place_loads(d, asm, 0.0_dp, placed, status)
    call assert_true(.not. status%ok .and. index(status%message, 'point_load_patch_m(1)') > 0, &
                     'a patch acting at its own point: refused ('//trim(status%message)//')')
  end subroutine test_patch

  !> Flamant's stress and its integrals against independent forms (the header).
  subroutine test_flamant()
    real(dp), parameter :: p_n = 1000.0_dp, z = 0.8_dp, patch = 0.4_dp, pi = acos(-1.0_dp)
    real(dp) :: a(2), bb(2), alpha, q
    integer :: k
    a = [-0.3_dp, 1.2_dp]
    bb = [0.7_dp, 2.5_dp]
    do k = 1, 2
      call assert_close(flamant_force(p_n, 0.0_dp, a(k), bb(k), z), simpson(p_n, 0.0_dp, a(k), bb(k), z), &
                        'Flamant: the integral of a point load''s stress over an interval, closed form', rtol=1.0e-10_dp)
      call assert_close(flamant_force(p_n, patch, a(k), bb(k), z), simpson(p_n, patch, a(k), bb(k), z), &
                        'Flamant: the integral of a patch''s stress over an interval, closed form', rtol=1.0e-10_dp)
    end do
    call assert_close(flamant_force(p_n, 0.0_dp, -1.0e7_dp, 1.0e7_dp, z), p_n, 'Flamant: a point load''s stress '// &
                      'over the whole line is the load', rtol=1.0e-12_dp)
    call assert_close(flamant_force(p_n, patch, -1.0e3_dp, 1.0e3_dp, z), p_n, 'Flamant: a patch''s stress '// &
                      'over 1 km either side (2e-10 beyond) is the load', rtol=1.0e-9_dp)
    q = p_n/patch
    alpha = 2.0_dp*atan(0.5_dp*patch/z)
    call assert_close(flamant_pressure(p_n, patch, 0.0_dp, z), q/pi*(alpha + sin(alpha)), &
                      'Flamant: a patch''s stress on its centre line, (q/pi)(alpha + sin alpha)', rtol=1.0e-12_dp)
    alpha = atan(patch/z)
    call assert_close(flamant_pressure(p_n, patch, 0.5_dp*patch, z), q/pi*(alpha + sin(alpha)*cos(alpha)), &
                      'Flamant: a patch''s stress under its edge, (q/pi)(alpha + sin alpha cos alpha)', rtol=1.0e-12_dp)
    call assert_close(flamant_force(p_n, 1.0e-3_dp*z, a(1), bb(1), z), flamant_force(p_n, 0.0_dp, a(1), bb(1), z), &
                      'Flamant: a patch of 1e-3 of the depth carries what the point does', rtol=1.0e-6_dp)
  end subroutine test_flamant

  !> Simpson's rule on Flamant's stress of `load_n` over `patch_m` at depth `z_m`, over
  !> offsets from `lo` to `hi` (2000 pieces).
  real(dp) function simpson(load_n, patch_m, lo, hi, z_m) result(total)
    real(dp), intent(in) :: load_n, patch_m, lo, hi, z_m
    real(dp) :: step
    integer :: i
    step = (hi - lo)/2000
    total = flamant_pressure(load_n, patch_m, lo, z_m) + flamant_pressure(load_n, patch_m, hi, z_m)
    do i = 1, 1999
      total = total + merge(4.0_dp, 2.0_dp, mod(i, 2) == 1)*flamant_pressure(load_n, patch_m, lo + i*step, z_m)
    end do
    total = total*step/3.0_dp
  end function simpson

end program test_limit_loads
