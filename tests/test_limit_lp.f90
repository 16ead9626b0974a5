!> Tests of the limit analysis of any assembly by linear programming (voussoir_limit_lp,
!> voussoir_block_interfaces, voussoir_glpk) against answers derived independently: closed
!> forms for blocks, stacks and a wall panel, the exact four-hinge analysis of the seed
!> arches, and the refusals.
program test_limit_lp
  use voussoir_kinds, only: dp, pi
  use voussoir_status, only: status_t
  use voussoir_assembly, only: assembly_t, build_arch, role_voussoir, role_foundation
  use voussoir_wall_config, only: wall_config_t
  use voussoir_wall, only: build_wall, box, block_stack
  use voussoir_limit_analysis, only: limit_result_t, horizontal_capacity
  use voussoir_minimum_thickness, only: minimum_thickness
  use voussoir_block_interfaces, only: interface_set_t, find_interfaces
  use voussoir_limit_lp, only: block_loads_t, lp_result_t, block_loads, lp_capacity, nonassociative_capacity, &
                               joint_hinge, joint_sliding, joint_closed
  use voussoir_assert, only: assert_true, assert_close, assert_summary
  implicit none

  call test_block_tipping()
  call test_block_sliding()
  call test_two_block_stack()
  call test_block_on_incline(mu=0.6_dp)
  call test_block_on_incline(mu=0.35_dp)
  call test_wall_panel()
  call test_seed_arches()
  call test_minimum_thickness()
  call test_refusals()
  call assert_summary()

contains

  !> Blocks of width b and height h stacked on a driven base (body 1) that is wider.
  !> Both capacities of `asm` with friction mu at every interface.
  subroutine capacities(asm, mu, assoc, nonassoc, status)
    type(assembly_t), intent(in) :: asm
    real(dp), intent(in) :: mu
    type(lp_result_t), intent(out) :: assoc, nonassoc
    type(status_t), intent(inout) :: status
    type(interface_set_t) :: faces
    type(block_loads_t) :: loads
    real(dp), allocatable :: friction(:)
    integer :: steps
    logical :: converged
    call find_interfaces(asm, 1.0e-9_dp, 0.0_dp, faces, status)
    if (.not. status%ok) return
    call block_loads(asm, 700.0_dp, 0.145_dp, 9.81_dp, loads)
    allocate (friction(faces%n))
    friction = mu
    call lp_capacity(asm, faces, loads, friction, 0.0_dp*friction, assoc, status)
    if (.not. status%ok) return
    call nonassociative_capacity(asm, faces, loads, friction, assoc, nonassoc, steps, converged, status)
    call assert_true(converged, 'non-associative iteration converges')
  end subroutine capacities

  !> b/h = 0.4 with mu = 0.6: tips at b/h about the far corner (a hinge at the interface).
  subroutine test_block_tipping()
    type(assembly_t) :: asm
    type(lp_result_t) :: a, na
    type(status_t) :: status
    call block_stack(0.2_dp, 0.5_dp, 1, asm)
    call capacities(asm, 0.6_dp, a, na, status)
    call assert_true(status%ok, 'block tipping: solved')
    call assert_close(a%load_factor, 0.4_dp, 'block tips at b/h (associative)', rtol=1.0e-9_dp)
    call assert_close(na%load_factor, 0.4_dp, 'block tips at b/h (non-associative)', rtol=1.0e-9_dp)
    call assert_close(a%load_factor_upper, a%load_factor, 'block tipping: upper bound = lower bound', rtol=1.0e-9_dp)
    call assert_true(a%mode(1) == joint_hinge .and. a%pivot_end(1) > 0, 'block tips about one end')
    ! The whole weight W = 700 x 0.1 x 0.145 x 9.81 N bears on the pivot; the lifting end carries nothing.
    call assert_close(a%normal_n(a%pivot_end(1), 1), 700*0.1_dp*0.145_dp*9.81_dp, 'block tipping: W on the pivot', &
                      rtol=1.0e-9_dp)
    call assert_close(a%normal_n(3 - a%pivot_end(1), 1), 0.0_dp, 'block tipping: no force at the end that lifts', &
                      atol=1.0e-9_dp)
  end subroutine test_block_tipping

  !> b/h = 0.4 with mu = 0.3: slides at lambda = mu, associative or not.
  subroutine test_block_sliding()
    type(assembly_t) :: asm
    type(lp_result_t) :: a, na
    type(status_t) :: status
    call block_stack(0.2_dp, 0.5_dp, 1, asm)
    call capacities(asm, 0.3_dp, a, na, status)
    call assert_true(status%ok, 'block sliding: solved')
    call assert_close(a%load_factor, 0.3_dp, 'block slides at mu (associative)', rtol=1.0e-9_dp)
    call assert_close(na%load_factor, 0.3_dp, 'block slides at mu (non-associative)', rtol=1.0e-9_dp)
    call assert_true(a%mode(1) == joint_sliding, 'block: the joint slides (associative)')
    call assert_true(na%mode(1) == joint_sliding, 'block: the joint slides (non-associative)')
    call assert_close(na%load_factor_upper, na%load_factor, 'block sliding: upper = lower (non-assoc. step)', &
                      rtol=1.0e-9_dp)
  end subroutine test_block_sliding

  !> A block b x h = 0.2 x 0.4 m on a driven incline falling at alpha = 10 deg towards +x,
  !> under lambda g towards +x. In the incline's frame the load per weight is lambda cos a
  !> + sin a down the slope and cos a - lambda sin a into it: the block slides at
  !> lambda = tan(phi - alpha) (mu = tan phi) and tips about its down-slope corner when the
  !> load's line through the centroid reaches it, lambda = tan(atan(b/h) - alpha); the
  !> lesser governs (mu 0.6: tipping, 0.297; mu 0.35: sliding, 0.164).
  subroutine test_block_on_incline(mu)
    real(dp), intent(in) :: mu
    real(dp), parameter :: alpha = 10.0_dp*pi/180.0_dp, b = 0.2_dp, h = 0.4_dp
    type(assembly_t) :: asm
    type(lp_result_t) :: a, na
    type(status_t) :: status
    real(dp) :: t(2), n(2), p0(2), lambda_slide, lambda_tip, expected
    character(len=:), allocatable :: what
    t = [cos(alpha), -sin(alpha)]    ! down the slope
    n = [sin(alpha), cos(alpha)]     ! out of the incline
    p0 = [-0.1_dp, 0.0_dp]
    asm%n_bodies = 2
    allocate (asm%polygon(2), asm%driven(2))
    asm%polygon(1)%xy = reshape([p0, p0 + b*t, p0 + b*t + h*n, p0 + h*n], [2, 4])
    ! The incline: a quadrilateral under the block's base, longer than it both ways.
    asm%polygon(2)%xy = reshape([p0 - 0.3_dp*t - [0.0_dp, 0.5_dp], p0 + (b + 0.3_dp)*t - [0.0_dp, 0.5_dp], &
                                 p0 + (b + 0.3_dp)*t, p0 - 0.3_dp*t], [2, 4])
    asm%driven = [.false., .true.]
    call capacities(asm, mu, a, na, status)
    what = 'block on a 10 deg incline, mu '//trim(adjustl(fmt_mu(mu)))
    call assert_true(status%ok, what//': solved')
    if (.not. status%ok) return
    lambda_slide = tan(atan(mu) - alpha)
    lambda_tip = tan(atan(b/h) - alpha)
    expected = min(lambda_slide, lambda_tip)
    call assert_close(a%load_factor, expected, what//': lambda = min(tan(phi - a), tan(atan(b/h) - a))', &
                      rtol=1.0e-9_dp)
    call assert_close(na%load_factor, expected, what//': the same without dilatancy', rtol=1.0e-9_dp)
    if (lambda_tip < lambda_slide) then
      call assert_true(a%mode(1) == joint_hinge, what//': it tips')
    else
      call assert_true(a%mode(1) == joint_sliding .and. na%mode(1) == joint_sliding, what//': it slides')
    end if
  end subroutine test_block_on_incline

  function fmt_mu(mu) result(text)
    real(dp), intent(in) :: mu
    character(len=16) :: text
    write (text, '(f5.2)') mu
  end function fmt_mu

  !> Two equal blocks, b/h = 0.4, mu = 0.8: the stack tips about the base's corner at b/(2h).
  subroutine test_two_block_stack()
    type(assembly_t) :: asm
    type(lp_result_t) :: a, na
    type(status_t) :: status
    call block_stack(0.2_dp, 0.5_dp, 2, asm)
    call capacities(asm, 0.8_dp, a, na, status)
    call assert_true(status%ok, 'stack: solved')
    call assert_close(a%load_factor, 0.2_dp, 'two-block stack tips at b/(2h)', rtol=1.0e-9_dp)
    call assert_close(na%load_factor, 0.2_dp, 'two-block stack (non-associative)', rtol=1.0e-9_dp)
  end subroutine test_two_block_stack

  !> A panel of 6 courses of 4 blocks (0.2 x 0.1 m) in stack bond, mu = 20: B/H = 0.8/0.6.
  subroutine test_wall_panel()
    type(assembly_t) :: asm
    type(wall_config_t) :: w
    type(lp_result_t) :: a, na
    type(status_t) :: status
    w%courses = 6
    w%blocks_per_course = 4
    w%bond = 'stack'
    call build_wall(w, asm)
    call capacities(asm, 20.0_dp, a, na, status)
    call assert_true(status%ok, 'wall panel: solved')
    ! Without dilatancy the vertical joints (no normal force) can slide: never above B/H.
    call assert_true(na%load_factor <= a%load_factor*(1 + 1.0e-9_dp), 'stack-bond panel: non-associative <= associative')
    call assert_close(a%load_factor, 0.8_dp/0.6_dp, 'stack-bond panel tips at B/H (associative)', rtol=1.0e-9_dp)
    call assert_close(a%load_factor_upper, a%load_factor, 'wall panel: upper = lower', rtol=1.0e-7_dp)
  end subroutine test_wall_panel

  !> The LP's lambda equals the exact four-hinge analysis on the seed arches (friction 10:
  !> sliding does not govern), with and without an inset.
  subroutine test_seed_arches()
    real(dp), parameter :: embrace(4) = [180.0_dp, 156.0_dp, 132.0_dp, 118.0_dp]
    integer, parameter :: nv(4) = [15, 13, 11, 10]
    type(assembly_t) :: arch
    type(limit_result_t) :: exact
    type(interface_set_t) :: faces
    type(block_loads_t) :: loads
    type(lp_result_t) :: a
    type(status_t) :: status
    real(dp), allocatable :: friction(:)
    real(dp) :: inset
    integer :: k, i
    character(len=40) :: name
    do i = 1, 2
      inset = merge(0.0_dp, 0.005_dp, i == 1)
      do k = 1, 4
        write (name, '(a,i0,a,f5.3)') 'seed arch ', nint(embrace(k)), ' inset ', inset
        call build_arch(embrace(k), nv(k), 0.508_dp, 0.071_dp, arch)
        call horizontal_capacity(arch, inset, 10.0_dp, exact, status)
        call find_interfaces(arch, 1.0e-9_dp, inset, faces, status)
        call block_loads(arch, 700.0_dp, 0.145_dp, 9.81_dp, loads)
        friction = spread(10.0_dp, 1, faces%n)
        call lp_capacity(arch, faces, loads, friction, 0.0_dp*friction, a, status)
        call assert_true(status%ok .and. faces%n == nv(k) + 1, trim(name)//': n + 1 joints, solved')
        call assert_close(a%load_factor, exact%lambda_pos, trim(name)//': LP lambda = four-hinge lambda', &
                          rtol=1.0e-6_dp)
        call assert_close(a%load_factor_upper, a%load_factor, trim(name)//': upper = lower', rtol=1.0e-6_dp)
        call assert_true(count(a%mode == joint_hinge) == 4 .and. count(a%mode == joint_closed) == nv(k) - 3, &
                         trim(name)//': four hinges, the other joints closed')
      end do
    end do
  end subroutine test_seed_arches

  !> The LP's own minimum thickness is that of the exact analysis (minimum_thickness: a
  !> symmetric thrust line, golden section and bisection; 0.10188 r_ext published for 20
  !> chord-faced voussoirs) to 1e-6: the semicircle of 20 voussoirs (r_ext 1 m, no inset,
  !> friction 10) carries its weight 1e-6 above that thickness, with a load factor that
  !> vanishes there, and cannot 1e-6 below it (infeasible: the dead load alone).
  subroutine test_minimum_thickness()
    type(assembly_t) :: arch
    type(interface_set_t) :: faces
    type(block_loads_t) :: loads
    type(lp_result_t) :: a
    type(status_t) :: status
    real(dp) :: ratio_ext, ratio_mean
    integer, allocatable :: hinges(:), sides(:)
    call minimum_thickness(180.0_dp, 20, 1.0_dp, 0.0_dp, ratio_ext, ratio_mean, hinges, sides, status)
    call assert_true(status%ok, 'minimum thickness of 20 voussoirs found')
    call build_arch(180.0_dp, 20, 1.0_dp, ratio_ext*(1 + 1.0e-6_dp), arch)
    call find_interfaces(arch, 1.0e-9_dp, 0.0_dp, faces, status)
    call block_loads(arch, 700.0_dp, 0.145_dp, 9.81_dp, loads)
    call lp_capacity(arch, faces, loads, spread(10.0_dp, 1, faces%n), spread(0.0_dp, 1, faces%n), a, status)
    call assert_true(status%ok, '20 voussoirs, 1e-6 above the minimum thickness: the LP carries the weight')
    call assert_true(a%load_factor >= 0.0_dp .and. a%load_factor < 1.0e-4_dp, &
                     '20 voussoirs, 1e-6 above the minimum thickness: the load factor vanishes')
    status = status_t()
    call build_arch(180.0_dp, 20, 1.0_dp, ratio_ext*(1 - 1.0e-6_dp), arch)
    call find_interfaces(arch, 1.0e-9_dp, 0.0_dp, faces, status)
    call block_loads(arch, 700.0_dp, 0.145_dp, 9.81_dp, loads)
    call lp_capacity(arch, faces, loads, spread(10.0_dp, 1, faces%n), spread(0.0_dp, 1, faces%n), a, status)
    call assert_true(.not. status%ok .and. index(status%message, 'dead load alone') > 0, &
                     '20 voussoirs, 1e-6 below the minimum thickness: infeasible, the dead load alone')
  end subroutine test_minimum_thickness

  !> A block whose centroid overhangs its support falls under its own weight (infeasible);
  !> a block against a driven wall on its +x side carries any lambda (unbounded); a block
  !> touching nothing is refused by name.
  subroutine test_refusals()
    type(assembly_t) :: asm
    type(lp_result_t) :: a, na
    type(status_t) :: status
    call block_stack(0.2_dp, 0.5_dp, 1, asm)
    asm%polygon(1)%xy = box(-1.0_dp, 0.05_dp, -0.5_dp, 0.0_dp)
    call capacities(asm, 0.8_dp, a, na, status)
    call assert_true(.not. status%ok .and. index(status%message, 'dead load alone') > 0, &
                     'overhanging block: infeasible, dead load named')
    call block_stack(0.2_dp, 0.5_dp, 1, asm)
    asm%polygon = [asm%polygon, asm%polygon(1)]
    asm%polygon(3)%xy = box(0.2_dp, 0.4_dp, 0.0_dp, 1.0_dp)
    asm%driven = [asm%driven, .true.]
    asm%role = [asm%role, role_foundation]
    asm%n_bodies = 3
    status = status_t()
    call capacities(asm, 0.8_dp, a, na, status)
    call assert_true(.not. status%ok .and. index(status%message, 'unbounded') > 0, &
                     'block against a driven wall: unbounded, said so')
  end subroutine test_refusals

end program test_limit_lp
