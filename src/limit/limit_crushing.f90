!> A finite compressive strength in the limit analysis by linear programming, as RING
!> and Gilbert take it: the compressive stress under an interface's normal force N is a
!> block of sigma_c over the width (out of plane) w, so its resultant stands at least
!> a = N / (2 sigma_c w) from either end of the interface (the crushing offset). Solved by
!> iteration: the LP with each interface's ends moved in by the offsets of the normal
!> forces of the solution before, from the rigid one, until lambda and the offsets no
!> longer change (1e-9 relative). docs/limit_analysis.md, "Crushing".
module voussoir_limit_crushing
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t
  use voussoir_assembly, only: assembly_t
  use voussoir_block_interfaces, only: interface_set_t
  use voussoir_limit_lp, only: block_loads_t, lp_result_t, lp_capacity, nonassociative_capacity
  implicit none
  private

  public :: crushing_t, crushed_faces, crushing_capacity, crushing_nonassociative, crushes

  integer, parameter :: max_steps = 200
  real(dp), parameter :: rel_tol = 1.0e-9_dp

  !> The compressive strength of the interfaces; rigid (no crushing) where not positive.
  type :: crushing_t
    real(dp) :: strength_pa = 0.0_dp  !! sigma_c [Pa], 0: infinite
    real(dp) :: width_m = 1.0_dp      !! the width out of plane w [m]
    !> Each interface's own sigma_c [Pa] where allocated (a bridge's parts; 0: that face
    !> does not crush), instead of strength_pa.
    real(dp), allocatable :: face_strength_pa(:)
  end type crushing_t

contains

  !> The interfaces `faces` with each end moved towards the other by the crushing offset
  !> N / (2 sigma_c w) of its normal force N [N]; an offset of half the interface or more
  !> leaves both ends at its middle (the interface crushed through: `crushed` is true).
  pure subroutine crushed_faces(faces, normal_n, crush, moved, crushed)
    type(interface_set_t), intent(in) :: faces
    real(dp), intent(in) :: normal_n(:)
    type(crushing_t), intent(in) :: crush
    type(interface_set_t), intent(out) :: moved
    logical, intent(out) :: crushed
    real(dp) :: along(2), half_m, offset_m
    integer :: k
    moved = faces
    crushed = .false.
    do k = 1, faces%n
      along = faces%end_xy(:, 2, k) - faces%end_xy(:, 1, k)
      half_m = 0.5_dp*norm2(along)
      offset_m = 0.0_dp
      if (face_strength(crush, k) > 0.0_dp) &
        offset_m = max(normal_n(k), 0.0_dp)/(2.0_dp*face_strength(crush, k)*crush%width_m)
      if (offset_m >= half_m) then
        crushed = .true.
        offset_m = half_m
      end if
      along = along/(2.0_dp*half_m)
      moved%end_xy(:, 1, k) = faces%end_xy(:, 1, k) + offset_m*along
      moved%end_xy(:, 2, k) = faces%end_xy(:, 2, k) - offset_m*along
    end do
  end subroutine crushed_faces

  !> The associative capacity with crushing (the rigid one where `crush` is rigid):
  !> `steps` LPs, `converged` when the offsets settled; after 20 steps the offsets move
  !> half-way only. `crushed`: an interface crushed through at the last step.
  subroutine crushing_capacity(asm, faces, loads, friction, crush, res, steps, converged, crushed, status)
    type(assembly_t), intent(in) :: asm
    type(interface_set_t), intent(in) :: faces
    type(block_loads_t), intent(in) :: loads
    real(dp), intent(in) :: friction(:)
    type(crushing_t), intent(in) :: crush
    type(lp_result_t), intent(out) :: res
    integer, intent(out) :: steps
    logical, intent(out) :: converged, crushed
    type(status_t), intent(inout) :: status
    type(interface_set_t) :: moved
    real(dp) :: normal(faces%n), previous_lambda
    steps = 1
    converged = .true.
    crushed = .false.
    call lp_capacity(asm, faces, loads, friction, 0.0_dp*friction, res, status)
    if (.not. status%ok .or. .not. crushes(crush)) return
    converged = .false.
    normal = sum(res%normal_n, dim=1)
    do steps = 2, max_steps
      previous_lambda = res%load_factor
      call crushed_faces(faces, normal, crush, moved, crushed)
      call lp_capacity(asm, moved, loads, friction, 0.0_dp*friction, res, status)
      if (.not. status%ok) return
      if (settled(res, previous_lambda, normal)) then
        converged = .true.
        return
      end if
      normal = relaxed(normal, sum(res%normal_n, dim=1), steps)
    end do
    steps = max_steps
  end subroutine crushing_capacity

  !> The non-associative capacity with crushing: the iteration of Gilbert, Casapulla and
  !> Ahmed on the interfaces moved in by the offsets of `assoc` (a solution with crushing),
  !> again with the offsets of its normal forces, until lambda and the offsets settle.
  !> `steps` counts the LPs of every round.
  subroutine crushing_nonassociative(asm, faces, loads, friction, crush, assoc, res, steps, converged, status)
    type(assembly_t), intent(in) :: asm
    type(interface_set_t), intent(in) :: faces
    type(block_loads_t), intent(in) :: loads
    real(dp), intent(in) :: friction(:)
    type(crushing_t), intent(in) :: crush
    type(lp_result_t), intent(in) :: assoc
    type(lp_result_t), intent(out) :: res
    integer, intent(out) :: steps
    logical, intent(out) :: converged
    type(status_t), intent(inout) :: status
    type(interface_set_t) :: moved
    type(lp_result_t) :: start
    real(dp) :: normal(faces%n), previous_lambda
    integer :: round, round_steps
    logical :: crushed, round_converged
    if (.not. crushes(crush)) then
      call nonassociative_capacity(asm, faces, loads, friction, assoc, res, steps, converged, status)
      return
    end if
    start = assoc
    normal = sum(assoc%normal_n, dim=1)
    previous_lambda = assoc%load_factor
    steps = 0
    converged = .false.
    do round = 1, max_steps
      call crushed_faces(faces, normal, crush, moved, crushed)
      call nonassociative_capacity(asm, moved, loads, friction, start, res, round_steps, round_converged, status)
      steps = steps + round_steps
      if (.not. status%ok) return
      if (round > 1 .and. round_converged .and. settled(res, previous_lambda, normal)) then
        converged = .true.
        return
      end if
      previous_lambda = res%load_factor
      normal = relaxed(normal, sum(res%normal_n, dim=1), round)
      start = res
    end do
  end subroutine crushing_nonassociative

  !> Whether any interface crushes.
  pure logical function crushes(crush)
    type(crushing_t), intent(in) :: crush
    crushes = crush%strength_pa > 0.0_dp
    if (allocated(crush%face_strength_pa)) crushes = any(crush%face_strength_pa > 0.0_dp)
  end function crushes

  !> Interface k's sigma_c [Pa] (0: it does not crush).
  pure real(dp) function face_strength(crush, k)
    type(crushing_t), intent(in) :: crush
    integer, intent(in) :: k
    face_strength = crush%strength_pa
    if (allocated(crush%face_strength_pa)) face_strength = crush%face_strength_pa(k)
  end function face_strength

  !> lambda and the interfaces' normal forces (so their offsets) within 1e-9 of the step before.
  pure logical function settled(res, previous_lambda, previous_normal)
    type(lp_result_t), intent(in) :: res
    real(dp), intent(in) :: previous_lambda, previous_normal(:)
    real(dp) :: normal(size(previous_normal))
    normal = sum(res%normal_n, dim=1)
    settled = abs(res%load_factor - previous_lambda) <= rel_tol*max(1.0_dp, abs(res%load_factor)) .and. &
              all(abs(normal - previous_normal) <= rel_tol*max(maxval([0.0_dp, abs(normal)]), tiny(1.0_dp)))
  end function settled

  !> The normal forces the next offsets come from: the new ones, half-way after 20 steps.
  pure function relaxed(old, new, step) result(next)
    real(dp), intent(in) :: old(:), new(:)
    integer, intent(in) :: step
    real(dp) :: next(size(old))
    real(dp) :: alpha
    alpha = merge(1.0_dp, 0.5_dp, step <= 20)
    next = (1.0_dp - alpha)*old + alpha*new
  end function relaxed

end module voussoir_limit_crushing
