!> The linear-programming limit analysis that voussoir-limit makes of any assembly
!> (voussoir_limit_lp): the interfaces, both capacities (associative and
!> non-associative) and, for an arch, the joint and side of every interface.
!> docs/limit_analysis.md, "Any assembly".
module voussoir_limit_lp_study
  use voussoir_kinds, only: dp, g_m_s2
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa
  use voussoir_assembly, only: assembly_t
  use voussoir_hinge_side, only: side_intrados, side_extrados
  use voussoir_block_interfaces, only: interface_set_t, find_interfaces
  use voussoir_limit_lp, only: block_loads_t, lp_result_t, block_loads, lp_capacity, nonassociative_capacity
  implicit none
  private

  public :: lp_study_t, lp_study

  !> Both capacities of an assembly under the horizontal acceleration lambda g towards +x.
  type :: lp_study_t
    logical :: solved = .false.               !! the associative LP has a solution
    logical :: nonassociative_solved = .false.
    character(len=:), allocatable :: note     !! why not, when not solved
    character(len=:), allocatable :: assembly !! 'arch', 'wall' or 'polygon file'
    type(interface_set_t) :: faces
    type(lp_result_t) :: assoc, nonassoc
    integer :: steps = 0                      !! steps of the non-associative iteration
    logical :: converged = .false.
    integer, allocatable :: joint(:)          !! arch joint 0..n of each interface, -1 if none
    integer, allocatable :: end_side(:, :)    !! (2, n_interfaces) side_intrados / side_extrados of each end (arches)
  end type lp_study_t

contains

  !> The LP analysis of `asm` with Coulomb friction `friction` at every interface, the
  !> weights of density x area x width x g, and the interface ends set in by `inset_m`.
  !> A refusal (no interfaces, infeasible, unbounded) comes back in `status`.
  subroutine lp_study(asm, density_kg_m3, width_m, friction, inset_m, study, status)
    type(assembly_t), intent(in) :: asm
    real(dp), intent(in) :: density_kg_m3, width_m, friction, inset_m
    type(lp_study_t), intent(out) :: study
    type(status_t), intent(inout) :: status
    type(block_loads_t) :: loads
    real(dp), allocatable :: mu(:)
    real(dp) :: size_m
    integer :: b

    size_m = 0.0_dp
    do b = 1, asm%n_bodies
      size_m = max(size_m, maxval(maxval(asm%polygon(b)%xy, dim=2) - minval(asm%polygon(b)%xy, dim=2)))
    end do
    ! Faces on one line to 1e-6 of the largest block (round-off of polygon files).
    call find_interfaces(asm, 1.0e-6_dp*size_m, inset_m, study%faces, status)
    if (.not. status%ok) return
    do b = 1, asm%n_bodies
      if (asm%driven(b) .or. any(study%faces%body == b)) cycle
      call fail(status, 'block '//itoa(b)//' touches no other block: nothing holds it up')
      return
    end do
    call name_arch_joints(asm, study)
    call block_loads(asm, density_kg_m3, width_m, g_m_s2, loads)
    allocate (mu(study%faces%n))
    mu = friction
    call lp_capacity(asm, study%faces, loads, mu, 0.0_dp*mu, study%assoc, status)
    if (.not. status%ok) return
    study%solved = .true.
    call nonassociative_capacity(asm, study%faces, loads, mu, study%assoc, study%nonassoc, study%steps, &
                                 study%converged, status)
    study%nonassociative_solved = status%ok
  end subroutine lp_study

  !> For an arch, the joint j (0..n) of each interface (the one between the same two
  !> bodies) and which of its ends is on the intrados.
  pure subroutine name_arch_joints(asm, study)
    type(assembly_t), intent(in) :: asm
    type(lp_study_t), intent(inout) :: study
    integer :: k, j, e
    real(dp) :: d_in, d_ext
    allocate (study%joint(study%faces%n), study%end_side(2, study%faces%n))
    study%joint = -1
    study%end_side = 0
    if (.not. allocated(asm%joint_bodies)) return
    do k = 1, study%faces%n
      do j = lbound(asm%joint_bodies, 2), ubound(asm%joint_bodies, 2)
        if (all(asm%joint_bodies(:, j) == study%faces%body(:, k)) .or. &
            all(asm%joint_bodies(:, j) == study%faces%body(2:1:-1, k))) study%joint(k) = j
      end do
      j = study%joint(k)
      if (j < 0) cycle
      do e = 1, 2
        d_in = norm2(study%faces%end_xy(:, e, k) - asm%joint_intrados_xy(:, j))
        d_ext = norm2(study%faces%end_xy(:, e, k) - asm%joint_extrados_xy(:, j))
        study%end_side(e, k) = merge(side_intrados, side_extrados, d_in < d_ext)
      end do
    end do
  end subroutine name_arch_joints

end module voussoir_limit_lp_study
