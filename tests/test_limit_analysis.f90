!> Tests of the limit analysis (voussoir_limit_analysis): horizontal collapse multipliers of
!> arches and block chains, minimum thickness, inset pivots and the sliding check.
program test_limit_analysis
  use voussoir_kinds, only: dp, i8
  use voussoir_status, only: status_t
  use voussoir_assembly, only: assembly_t, build_arch, arch_joint_angle_deg
  use voussoir_hinge_side, only: side_intrados, side_extrados
  use voussoir_limit_analysis, only: block_chain_t, limit_result_t, &
                            chain_capacity, horizontal_capacity
  use voussoir_minimum_thickness, only: minimum_thickness
  use voussoir_assert, only: assert_true, assert_close, assert_summary
  implicit none

  call test_grows_with_thickness()
  call test_symmetric_directions()
  call test_inset_lowers_capacity()
  call test_independent_static_values()
  call test_rocking_block()
  call test_two_block_stack()
  call test_portal_by_hand()
  call test_minimum_thickness_20()
  call test_lambda_zero_at_minimum_thickness()
  call test_odd_voussoirs()
  call test_continuous_limit()
  call test_bad_input()
  call assert_summary()

contains

  !> A thicker arch (same embrace, voussoirs and extrados radius) carries more.
  subroutine test_grows_with_thickness()
    real(dp), parameter :: thickness_m(5) = [0.055_dp, 0.071_dp, 0.09_dp, 0.12_dp, 0.2_dp]
    real(dp) :: lambda(5)
    type(assembly_t) :: arch
    type(limit_result_t) :: res
    type(status_t) :: status
    integer :: k
    do k = 1, size(thickness_m)
      call build_arch(180.0_dp, 15, 0.508_dp, thickness_m(k), arch)
      call horizontal_capacity(arch, 0.0_dp, 0.5_dp, res, status)
      lambda(k) = res%lambda_pos
    end do
    call assert_true(status%ok, 'thickness sweep: status ok')
    call assert_true(all(lambda(2:) > lambda(:4)), 'thickness sweep: lambda grows with thickness')
    call assert_true(lambda(1) > 0.0_dp, 'thickness sweep: arch above minimum thickness stands')
  end subroutine test_grows_with_thickness

  !> The seed arches are symmetric: +x and -x agree and the mechanisms mirror (j <-> n - j).
  subroutine test_symmetric_directions()
    real(dp), parameter :: embrace_deg(4) = [180.0_dp, 156.0_dp, 132.0_dp, 118.0_dp]
    integer, parameter :: n_voussoirs(4) = [15, 13, 11, 10]
    real(dp), parameter :: inset_m(2) = [0.0_dp, 0.005_dp]
    type(assembly_t) :: arch
    type(limit_result_t) :: res
    type(status_t) :: status
    character(len=64) :: name
    integer :: k, i, n
    do i = 1, 2
      do k = 1, 4
        n = n_voussoirs(k)
        write (name, '(a,f5.1,a,i0,a,f5.3)') 'seed arch ', embrace_deg(k), '/', n, ' inset ', inset_m(i)
        call build_arch(embrace_deg(k), n, 0.508_dp, 0.071_dp, arch)
        call horizontal_capacity(arch, inset_m(i), 0.5_dp, res, status)
        call assert_true(status%ok, trim(name)//': status ok')
        call assert_close(res%lambda_neg, res%lambda_pos, trim(name)//': lambda -x = lambda +x', rtol=1.0e-9_dp)
        call assert_true(res%n_hinges_pos == 4 .and. res%n_hinges_neg == 4, trim(name)//': four hinges')
        call assert_true(all(res%hinges_neg == n - res%hinges_pos(4:1:-1)) &
                         .and. all(res%sides_neg == res%sides_pos(4:1:-1)), &
                         trim(name)//': -x mechanism mirrors +x')
        call assert_true(all(res%hinges_pos(2:) > res%hinges_pos(:3)), trim(name)//': hinges ascending')
        call assert_true(res%bounds_meet_pos .and. res%bounds_meet_neg, trim(name)//': bounds meet')
        call assert_close(res%lambda_static_pos, res%lambda_pos, trim(name)//': static = kinematic', &
                          rtol=1.0e-9_dp)
      end do
    end do
  end subroutine test_symmetric_directions

  !> Setting the pivots in shortens every lever arm: the capacity drops.
  subroutine test_inset_lowers_capacity()
    type(assembly_t) :: arch
    type(limit_result_t) :: res0, res1
    type(status_t) :: status
    call build_arch(156.0_dp, 13, 0.508_dp, 0.071_dp, arch)
    call horizontal_capacity(arch, 0.0_dp, 0.5_dp, res0, status)
    call horizontal_capacity(arch, 0.005_dp, 0.5_dp, res1, status)
    call assert_true(status%ok .and. res1%lambda_pos < res0%lambda_pos, 'inset lowers the capacity')
  end subroutine test_inset_lowers_capacity

  !> Values from an independent static (lower-bound) computation: a Python script (not
  !> this module) that builds the same chord-faced arch, writes the no-tension condition
  !> at every joint as two linear inequalities in (H, V, M0, lambda) and maximises lambda
  !> by enumerating every vertex of that 4-D polytope (numpy, 35 960 vertices for 15
  !> voussoirs). Bound theorems: the kinematic minimum must equal that static maximum.
  subroutine test_independent_static_values()
    type(assembly_t) :: arch
    type(limit_result_t) :: res
    type(status_t) :: status
    call build_arch(180.0_dp, 15, 0.508_dp, 0.071_dp, arch)
    call horizontal_capacity(arch, 0.0_dp, 0.5_dp, res, status)
    call assert_close(res%lambda_pos, 0.1513647731436337_dp, '180/15 lambda (static LP)', rtol=1.0e-9_dp)
    call horizontal_capacity(arch, 0.005_dp, 0.5_dp, res, status)
    call assert_close(res%lambda_pos, 0.08063660945800422_dp, '180/15 inset 5 mm lambda (static LP)', &
                      rtol=1.0e-9_dp)
    call build_arch(118.0_dp, 10, 0.508_dp, 0.071_dp, arch)
    call horizontal_capacity(arch, 0.0_dp, 0.5_dp, res, status)
    call assert_close(res%lambda_pos, 0.9805380116427077_dp, '118/10 lambda (static LP)', rtol=1.0e-9_dp)
  end subroutine test_independent_static_values

  !> One free block 2b x 2h on a driven base. It tips about a bottom corner when
  !> lambda g exceeds g b / h (moments of W and lambda W about the corner); with the
  !> pivot set in by e the lever arm of the weight is b - e: lambda = (b - e) / h.
  !> At collapse the base carries N = W and shear lambda W: shear ratio = lambda.
  subroutine test_rocking_block()
    real(dp), parameter :: b = 0.1_dp, h = 0.4_dp, e = 0.02_dp
    type(block_chain_t) :: chain
    type(limit_result_t) :: res
    type(status_t) :: status
    chain%n_blocks = 1
    chain%free_top = .true.
    chain%weight = [4.0_dp*b*h]
    chain%centroid_xy = reshape([0.0_dp, h], [2, 1])
    ! Joint 0: the base (intrados end at the left corner); joint 1: the free top.
    chain%joint_intrados_xy = reshape([-b, 0.0_dp, -b, 2.0_dp*h], [2, 2])
    chain%joint_extrados_xy = reshape([b, 0.0_dp, b, 2.0_dp*h], [2, 2])

    call chain_capacity(chain, 0.0_dp, 0.3_dp, res, status)
    call assert_true(status%ok, 'rocking block: status ok')
    call assert_close(res%lambda_pos, b/h, 'rocking block: lambda +x = b/h', rtol=1.0e-12_dp)
    call assert_close(res%lambda_neg, b/h, 'rocking block: lambda -x = b/h', rtol=1.0e-12_dp)
    call assert_true(res%n_hinges_pos == 1 .and. res%hinges_pos(1) == 0 .and. &
                     res%sides_pos(1) == side_extrados, 'rocking block: +x tips about the right corner')
    call assert_true(res%hinges_neg(1) == 0 .and. res%sides_neg(1) == side_intrados, &
                     'rocking block: -x tips about the left corner')
    call assert_true(res%bounds_meet_pos .and. res%bounds_meet_neg, 'rocking block: bounds meet')
    call assert_close(res%shear_ratio_pos(0), b/h, 'rocking block: base shear ratio = lambda', rtol=1.0e-12_dp)
    call assert_true(size(res%sliding_joints_pos) == 0, 'rocking block: mu 0.3 > 0.25, hinging governs')

    call chain_capacity(chain, e, 0.22_dp, res, status)
    call assert_close(res%lambda_pos, (b - e)/h, 'rocking block inset: lambda +x = (b-e)/h', rtol=1.0e-12_dp)
    call assert_close(res%lambda_neg, (b - e)/h, 'rocking block inset: lambda -x = (b-e)/h', rtol=1.0e-12_dp)
    call assert_true(size(res%sliding_joints_pos) == 0, 'rocking block inset: mu 0.22 > 0.2, no sliding')

    call chain_capacity(chain, 0.0_dp, 0.22_dp, res, status)
    call assert_true(size(res%sliding_joints_pos) == 1, 'rocking block: mu 0.22 < 0.25, one sliding joint')
    if (size(res%sliding_joints_pos) == 1) &
      call assert_true(res%sliding_joints_pos(1) == 0, 'rocking block: sliding governs at the base')
  end subroutine test_rocking_block

  !> Two stacked blocks: base 0.4 x 0.4 (W1 = 0.16 at y 0.2), a slender top 0.1 x 0.4
  !> (W2 = 0.04 at y 0.6). Top block alone about its corner: lambda = 0.05 / 0.2 = 0.25.
  !> Whole stack about the base corner (0.2, 0): lambda = (0.16*0.2 + 0.04*0.2) /
  !> (0.16*0.2 + 0.04*0.6) = 0.04 / 0.056 = 0.714. The top block governs.
  subroutine test_two_block_stack()
    type(block_chain_t) :: chain
    type(limit_result_t) :: res
    type(status_t) :: status
    chain%n_blocks = 2
    chain%free_top = .true.
    chain%weight = [0.16_dp, 0.04_dp]
    chain%centroid_xy = reshape([0.0_dp, 0.2_dp, 0.0_dp, 0.6_dp], [2, 2])
    chain%joint_intrados_xy = reshape([-0.2_dp, 0.0_dp, -0.05_dp, 0.4_dp, -0.05_dp, 0.8_dp], [2, 3])
    chain%joint_extrados_xy = reshape([0.2_dp, 0.0_dp, 0.05_dp, 0.4_dp, 0.05_dp, 0.8_dp], [2, 3])
    call chain_capacity(chain, 0.0_dp, 0.5_dp, res, status)
    call assert_close(res%lambda_pos, 0.25_dp, 'two-block stack: top block tips first', rtol=1.0e-12_dp)
    call assert_true(res%hinges_pos(1) == 1, 'two-block stack: hinge at joint 1')
    call assert_true(res%bounds_meet_pos, 'two-block stack: base joint holds the thrust')
  end subroutine test_two_block_stack

  !> A three-block portal computed by hand.
  !>
  !> Left column x in [0, 0.2], right column x in [0.7, 1.0], both y in [0, 1]; lintel
  !> x in [0, 1], y in [1, 1.2]. Weights (areas) W1 = 0.2, W2 = 0.2, W3 = 0.3; centroids
  !> G1 = (0.1, 0.5), G2 = (0.5, 1.1), G3 = (0.85, 0.5). Joints (intrados = inner corner,
  !> extrados = outer corner): j0 (0.2,0)/(0,0), j1 (0.2,1)/(0,1), j2 (0.7,1)/(1,1),
  !> j3 (0.7,0)/(1,0). The only hinge set is A, B, C, D at joints 0..3.
  !>
  !> Kinematics (omega1 = 1): omega2 (C - B) + omega3 (D - C) = A - B. B and C are at
  !> y = 1, A and D at y = 0, so the y row gives omega3 = omega1 and
  !> omega2 = ((Cx - Dx) - (Bx - Ax)) / (Cx - Bx).
  !> Opening (the other corner must separate): joint 0 int lifts the left corner only if
  !> omega1 < 0, ext only if omega1 > 0; joint 3 int needs omega3 > 0, ext omega3 < 0.
  !> Joint 1 (relative rotation omega2 - omega1): int needs < 0, ext > 0. Joint 2
  !> (relative rotation omega3 - omega2): int needs < 0, ext > 0. As omega3 = omega1, the
  !> bases are (A int, D ext) with omega1 = -1 or (A ext, D int) with omega1 = +1.
  !> Family omega1 = -1 (A = (0.2,0), D = (1,0)), omega2 = -((Cx - 1) - (Bx - 0.2))/(Cx - Bx):
  !>   B needs omega2 < -1 (int) or > -1 (ext); C needs omega2 > -1 (int) or < -1 (ext):
  !>   (B ext, C int) 1/7 opens both; (B ext, C ext) -0.2, (B int, C int) 0.6 and
  !>   (B int, C ext) 0 do not.
  !> Family omega1 = +1 (A = (0,0), D = (0.7,0)), omega2 = ((Cx - 0.7) - Bx)/(Cx - Bx):
  !>   B needs omega2 < 1 (int) or > 1 (ext); C needs omega2 > 1 (int) or < 1 (ext):
  !>   (B int, C ext) 1/8 opens both; (B int, C int) -0.4, (B ext, C int) 0 and
  !>   (B ext, C ext) 0.3 do not. One admissible mechanism per direction of sway; the
  !>   same holds with the inset below (omega2 = 1/7, -1/6, 0.48, 0 and 1/8, -0.30, 0, 0.27).
  !> +x: A = (0.2,0), B = (0,1), C = (0.7,1), D = (1,0); omega2' = (-0.3 + 0.2) / 0.7 = -1/7,
  !> so with omega1 = omega3 = -1, omega2 = 1/7. Velocities v = omega perp(G - pivot):
  !>   column 1: (0.5, 0.1); lintel: v_B = (1, 0.2), v(G2) = v_B + (1/7)(-0.1, 0.5)
  !>   = (69/70, 19/70); column 3: (0.5, 0.15) (check v_C = (1, 0.3) both ways).
  !>   sum W v_y = 0.02 + 3.8/70 + 0.045 = 8.35/70; sum W v_x = 0.1 + 13.8/70 + 0.15 = 31.3/70
  !>   lambda+ = 8.35 / 31.3 = 167/626 = 0.266773...
  !> -x: A = (0,0), B = (0.2,1), C = (1,1), D = (0.7,0); omega2 = (0.3 - 0.2) / 0.8 = 1/8,
  !>   omega1 = omega3 = 1. column 1: (-0.5, 0.1); lintel v_B = (-1, 0.2),
  !>   v(G2) = (-1, 0.2) + (1/8)(-0.1, 0.3) = (-1.0125, 0.2375); column 3: (-0.5, 0.15).
  !>   sum W v_y = 0.02 + 0.0475 + 0.045 = 0.1125; sum W v_x = -0.4525
  !>   lambda- = 0.1125 / 0.4525 = 45/181 = 0.248618...
  !> Inset e = 0.02 (pivots 0.02 in from the corners):
  !> +x: A = (0.18,0), B = (0.02,1), C = (0.72,1), D = (0.98,0); omega2' = (-0.26 + 0.16)/0.7
  !>   = -1/7 again. column 1: (0.5, 0.08); v_B = (1, 0.16), v(G2) = (1, 0.16) + (1/7)(-0.1,
  !>   0.48) = (69/70, 16/70); column 3: (0.5, 0.13).
  !>   sum W v_y = 0.016 + 3.2/70 + 0.039 = 7.05/70; sum W v_x = 31.3/70
  !>   lambda+ = 7.05 / 31.3 = 141/626 = 0.225239...
  !> -x: A = (0.02,0), B = (0.18,1), C = (0.98,1), D = (0.72,0); omega2 = (0.26 - 0.16)/0.8
  !>   = 1/8. column 1: (-0.5, 0.08); v_B = (-1, 0.16), v(G2) = (-1, 0.16) + (1/8)(-0.1, 0.32)
  !>   = (-1.0125, 0.2); column 3: (-0.5, 0.13).
  !>   sum W v_y = 0.016 + 0.04 + 0.039 = 0.095; sum W v_x = -0.4525
  !>   lambda- = 0.095 / 0.4525 = 38/181 = 0.209944...
  subroutine test_portal_by_hand()
    type(block_chain_t) :: chain
    type(limit_result_t) :: res
    type(status_t) :: status
    chain%n_blocks = 3
    chain%free_top = .false.
    chain%weight = [0.2_dp, 0.2_dp, 0.3_dp]
    chain%centroid_xy = reshape([0.1_dp, 0.5_dp, 0.5_dp, 1.1_dp, 0.85_dp, 0.5_dp], [2, 3])
    chain%joint_intrados_xy = reshape([0.2_dp, 0.0_dp, 0.2_dp, 1.0_dp, 0.7_dp, 1.0_dp, 0.7_dp, 0.0_dp], [2, 4])
    chain%joint_extrados_xy = reshape([0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp, 0.0_dp], [2, 4])

    call chain_capacity(chain, 0.0_dp, 0.5_dp, res, status)
    call assert_true(status%ok, 'portal: status ok')
    call assert_close(res%lambda_pos, 167.0_dp/626.0_dp, 'portal: lambda +x by hand', rtol=1.0e-9_dp)
    call assert_close(res%lambda_neg, 45.0_dp/181.0_dp, 'portal: lambda -x by hand', rtol=1.0e-9_dp)
    call assert_true(all(res%hinges_pos == [0, 1, 2, 3]) .and. &
                     all(res%sides_pos == [side_intrados, side_extrados, side_intrados, side_extrados]), &
                     'portal: +x hinges int, ext, int, ext')
    call assert_true(all(res%sides_neg == [side_extrados, side_intrados, side_extrados, side_intrados]), &
                     'portal: -x hinges ext, int, ext, int')
    call assert_true(res%bounds_meet_pos .and. res%bounds_meet_neg, 'portal: bounds meet')

    call chain_capacity(chain, 0.02_dp, 0.5_dp, res, status)
    call assert_close(res%lambda_pos, 141.0_dp/626.0_dp, 'portal inset: lambda +x by hand', rtol=1.0e-9_dp)
    call assert_close(res%lambda_neg, 38.0_dp/181.0_dp, 'portal inset: lambda -x by hand', rtol=1.0e-9_dp)
    call assert_true(res%bounds_meet_pos .and. res%bounds_meet_neg, 'portal inset: bounds meet')
  end subroutine test_portal_by_hand

  !> Semicircle of 20 chord-faced voussoirs: t/R_ext = 0.10188 (published value); the
  !> hinges sit at the springings, the crown joint (extrados) and the joints nearest
  !> 54.5 deg from the crown (joints 4 and 16, 54 deg), on the intrados.
  subroutine test_minimum_thickness_20()
    real(dp) :: ratio_ext, ratio_mean
    integer, allocatable :: hinges(:), sides(:)
    type(status_t) :: status
    call minimum_thickness(180.0_dp, 20, 0.508_dp, 0.0_dp, ratio_ext, ratio_mean, hinges, sides, status)
    call assert_true(status%ok, 'minimum thickness 20: status ok')
    call assert_close(ratio_ext, 0.10188_dp, 'minimum thickness 20: t/R_ext', atol=1.0e-4_dp)
    call assert_close(ratio_mean, ratio_ext/(1.0_dp - 0.5_dp*ratio_ext), 'minimum thickness 20: t/R_mean', &
                      rtol=1.0e-12_dp)
    call assert_true(size(hinges) == 5, 'minimum thickness 20: five hinges')
    if (size(hinges) == 5) then
      call assert_true(all(hinges == [0, 4, 10, 16, 20]), 'minimum thickness 20: hinges at 0, 4, 10, 16, 20')
      call assert_true(all(sides == [side_extrados, side_intrados, side_extrados, side_intrados, side_extrados]), &
                       'minimum thickness 20: sides ext, int, ext, int, ext')
    end if
  end subroutine test_minimum_thickness_20

  !> The four-hinge search and the symmetric equilibrium agree: lambda vanishes at the
  !> minimum thickness, is positive above it and negative below (both directions).
  subroutine test_lambda_zero_at_minimum_thickness()
    real(dp), parameter :: inset_m(2) = [0.0_dp, 0.004_dp]
    real(dp) :: ratio_ext, ratio_mean
    integer, allocatable :: hinges(:), sides(:)
    type(assembly_t) :: arch
    type(limit_result_t) :: res
    type(status_t) :: status
    character(len=32) :: name
    integer :: i
    do i = 1, 2
      write (name, '(a,f5.3)') 'lambda(t_min), inset ', inset_m(i)
      call minimum_thickness(156.0_dp, 13, 0.508_dp, inset_m(i), ratio_ext, ratio_mean, hinges, sides, status)
      call build_arch(156.0_dp, 13, 0.508_dp, ratio_ext*0.508_dp, arch)
      call horizontal_capacity(arch, inset_m(i), 0.5_dp, res, status)
      call assert_true(status%ok, trim(name)//': status ok')
      call assert_close(res%lambda_pos, 0.0_dp, trim(name)//': lambda +x = 0', atol=1.0e-6_dp)
      call assert_close(res%lambda_neg, 0.0_dp, trim(name)//': lambda -x = 0', atol=1.0e-6_dp)
      call build_arch(156.0_dp, 13, 0.508_dp, 1.01_dp*ratio_ext*0.508_dp, arch)
      call horizontal_capacity(arch, inset_m(i), 0.5_dp, res, status)
      call assert_true(res%lambda_pos > 0.0_dp .and. res%lambda_neg > 0.0_dp, trim(name)//': stands 1 % thicker')
      call build_arch(156.0_dp, 13, 0.508_dp, 0.99_dp*ratio_ext*0.508_dp, arch)
      call horizontal_capacity(arch, inset_m(i), 0.5_dp, res, status)
      call assert_true(res%lambda_pos < 0.0_dp .and. res%lambda_neg < 0.0_dp, trim(name)//': fails 1 % thinner')
    end do
    ! With pivots set in by e the thrust must fit a band t - 2e wide about the mean radius
    ! r_ext - t/2, so (t - 2e) / (r_ext - t/2) stays near the no-inset ratio rho = 0.10735
    ! (20 voussoirs; the weight distribution barely changes): t(1 + rho/2) = rho r_ext + 2e,
    ! i.e. the minimum thickness grows by 2e / (1 + rho/2) = 1.898 e.
    call minimum_thickness(180.0_dp, 20, 0.508_dp, 0.004_dp, ratio_ext, ratio_mean, hinges, sides, status)
    call assert_close((ratio_ext - 0.10188_dp)*0.508_dp, 2.0_dp*0.004_dp/(1.0_dp + 0.5_dp*0.10735_dp), &
                      'inset 4 mm raises the minimum thickness by 2e/(1 + rho/2) [m]', rtol=0.01_dp)
  end subroutine test_lambda_zero_at_minimum_thickness

  !> An odd number of voussoirs has a keystone instead of a crown joint: the symmetric
  !> mechanism opens both keystone joints on the extrados (six hinges).
  subroutine test_odd_voussoirs()
    real(dp) :: ratio_ext, ratio_mean
    integer, allocatable :: hinges(:), sides(:)
    type(status_t) :: status
    call minimum_thickness(180.0_dp, 21, 1.0_dp, 0.0_dp, ratio_ext, ratio_mean, hinges, sides, status)
    call assert_true(status%ok .and. size(hinges) == 6, 'odd voussoirs: six hinges')
    if (size(hinges) == 6) then
      call assert_true(hinges(3) == 10 .and. hinges(4) == 11 .and. sides(3) == side_extrados &
                       .and. sides(4) == side_extrados, 'odd voussoirs: keystone joints on the extrados')
      call assert_true(all(hinges == 21 - hinges(6:1:-1)), 'odd voussoirs: symmetric hinges')
    end if
  end subroutine test_odd_voussoirs

  !> Many voussoirs tend to Milankovitch's continuous arch: t/R_mean = 0.1075 with the
  !> haunch hinges 54.5 deg from the crown (within one voussoir).
  subroutine test_continuous_limit()
    integer, parameter :: n = 300
    real(dp) :: ratio_ext, ratio_mean, angle_deg
    integer, allocatable :: hinges(:), sides(:)
    type(status_t) :: status
    call minimum_thickness(180.0_dp, n, 2.0_dp, 0.0_dp, ratio_ext, ratio_mean, hinges, sides, status)
    call assert_true(status%ok, 'continuous limit: status ok')
    call assert_close(ratio_mean, 0.1075_dp, 'continuous limit: t/R_mean (Milankovitch)', rtol=2.0e-3_dp)
    call assert_true(size(hinges) == 5, 'continuous limit: five hinges')
    if (size(hinges) == 5) then
      angle_deg = abs(arch_joint_angle_deg(180.0_dp, n, hinges(2)) - 90.0_dp)
      call assert_close(angle_deg, 54.5_dp, 'continuous limit: haunch hinge from crown [deg]', &
                        atol=180.0_dp/n)
    end if
  end subroutine test_continuous_limit

  !> Inputs outside the model are reported through the status.
  subroutine test_bad_input()
    type(assembly_t) :: arch
    type(limit_result_t) :: res
    type(status_t) :: status
    real(dp) :: ratio_ext, ratio_mean
    integer, allocatable :: hinges(:), sides(:)
    call build_arch(180.0_dp, 15, 0.508_dp, 0.071_dp, arch)
    call horizontal_capacity(arch, 0.0356_dp, 0.5_dp, res, status)
    call assert_true(.not. status%ok, 'bad input: inset over half the joint is refused')
    status%ok = .true.
    call build_arch(180.0_dp, 2, 0.508_dp, 0.071_dp, arch)
    call horizontal_capacity(arch, 0.0_dp, 0.5_dp, res, status)
    call assert_true(.not. status%ok, 'bad input: two voussoirs have no four-hinge mechanism')
    status%ok = .true.
    call build_arch(180.0_dp, 15, 0.508_dp, 0.071_dp, arch, restrained=[.true., .false.])
    call horizontal_capacity(arch, 0.0_dp, 0.5_dp, res, status)
    call assert_true(.not. status%ok, 'bad input: restraint brackets are refused')
    status%ok = .true.
    call minimum_thickness(200.0_dp, 20, 0.508_dp, 0.0_dp, ratio_ext, ratio_mean, hinges, sides, status)
    call assert_true(.not. status%ok, 'bad input: embrace over 180 deg is refused')
  end subroutine test_bad_input

end program test_limit_analysis
