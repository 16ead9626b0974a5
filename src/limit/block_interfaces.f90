!> The interfaces of an assembly, found from its polygons alone: where a face of one
!> block and a face of another lie on one line with opposite outward normals and overlap
!> (within a tolerance). Each interface is a segment with two ends; the limit analysis
!> puts a normal force at each end (docs/limit_analysis.md, "Any assembly").
module voussoir_block_interfaces
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa
  use voussoir_assembly, only: assembly_t
  implicit none
  private

  public :: interface_set_t, find_interfaces

  !> The interfaces of an assembly. The force on body(2) from body(1) is counted positive.
  type :: interface_set_t
    integer :: n = 0
    integer, allocatable :: body(:, :)       !! (2, n) the two blocks
    real(dp), allocatable :: end_xy(:, :, :) !! (2, 2, n) the two ends [m], inset applied
    real(dp), allocatable :: normal(:, :)    !! (2, n) unit normal from body(1) into body(2)
  end type interface_set_t

contains

  !> Every interface of `asm` between two blocks not both driven. Faces are on one line
  !> when their vertices lie within `tol_m` of it and their normals are opposite to 1e-6;
  !> overlaps shorter than `tol_m` are ignored. The ends move towards each other by
  !> `inset_m` (the pivot inset of the four-hinge analysis); an interface not longer than
  !> 2 inset_m is refused.
  subroutine find_interfaces(asm, tol_m, inset_m, faces, status)
    type(assembly_t), intent(in) :: asm
    real(dp), intent(in) :: tol_m, inset_m
    type(interface_set_t), intent(out) :: faces
    type(status_t), intent(inout) :: status
    real(dp), allocatable :: lo(:, :), hi(:, :)
    integer, allocatable :: body(:, :)
    real(dp), allocatable :: ends(:, :, :), normal(:, :)
    real(dp) :: seg(2, 2), nrm(2)
    integer :: i, j, ei, ej, n, cap
    logical :: found

    allocate (lo(2, asm%n_bodies), hi(2, asm%n_bodies))
    do i = 1, asm%n_bodies
      lo(:, i) = minval(asm%polygon(i)%xy, dim=2) - tol_m
      hi(:, i) = maxval(asm%polygon(i)%xy, dim=2) + tol_m
    end do
    cap = 4*asm%n_bodies + 8
    allocate (body(2, cap), ends(2, 2, cap), normal(2, cap))
    n = 0
    do i = 1, asm%n_bodies
      do j = i + 1, asm%n_bodies
        if (asm%driven(i) .and. asm%driven(j)) cycle
        if (any(lo(:, j) > hi(:, i)) .or. any(lo(:, i) > hi(:, j))) cycle
        do ei = 1, size(asm%polygon(i)%xy, 2)
          do ej = 1, size(asm%polygon(j)%xy, 2)
            call face_overlap(asm%polygon(i)%xy, ei, asm%polygon(j)%xy, ej, tol_m, seg, nrm, found)
            if (.not. found) cycle
            if (n == cap) call grow(body, ends, normal, cap)
            n = n + 1
            body(:, n) = [i, j]
            normal(:, n) = nrm
            ends(:, :, n) = seg
          end do
        end do
      end do
    end do
    faces%n = n
    faces%body = body(:, 1:n)
    faces%normal = normal(:, 1:n)
    faces%end_xy = ends(:, :, 1:n)
    do i = 1, n
      call set_in(faces%end_xy(:, :, i), inset_m, found)
      if (.not. found) then
        call fail(status, 'the interface of blocks '//itoa(faces%body(1, i))//' and '//itoa(faces%body(2, i))// &
                  ' is not longer than twice the inset: lower inset_m')
        return
      end if
    end do
  end subroutine find_interfaces

  !> The overlap of edge ei of polygon a and edge ej of polygon b when they lie on one
  !> line facing each other; `nrm` is the outward normal of a's edge.
  pure subroutine face_overlap(a, ei, b, ej, tol_m, seg, nrm, found)
    real(dp), intent(in) :: a(:, :), b(:, :), tol_m
    integer, intent(in) :: ei, ej
    real(dp), intent(out) :: seg(2, 2), nrm(2)
    logical, intent(out) :: found
    real(dp) :: p0(2), p1(2), q0(2), q1(2), t(2), len_a, s0, s1, sa, sb
    p0 = a(:, ei)
    p1 = a(:, modulo(ei, size(a, 2)) + 1)
    q0 = b(:, ej)
    q1 = b(:, modulo(ej, size(b, 2)) + 1)
    found = .false.
    seg = 0.0_dp
    len_a = norm2(p1 - p0)
    t = (p1 - p0)/len_a
    nrm = [t(2), -t(1)]                       ! outward for counter-clockwise vertices
    if (dot_product(q1 - q0, t) > -(1.0_dp - 1.0e-6_dp)*norm2(q1 - q0)) return
    if (abs(dot_product(q0 - p0, nrm)) > tol_m .or. abs(dot_product(q1 - p0, nrm)) > tol_m) return
    s0 = dot_product(q1 - p0, t)              ! b's edge runs the other way
    s1 = dot_product(q0 - p0, t)
    sa = max(0.0_dp, s0)
    sb = min(len_a, s1)
    if (sb - sa <= tol_m) return
    found = .true.
    seg(:, 1) = p0 + sa*t
    seg(:, 2) = p0 + sb*t
  end subroutine face_overlap

  !> Move both ends of `seg` towards each other by `inset_m`; ok = .false. when they would cross.
  pure subroutine set_in(seg, inset_m, ok)
    real(dp), intent(inout) :: seg(2, 2)
    real(dp), intent(in) :: inset_m
    logical, intent(out) :: ok
    real(dp) :: t(2), length
    length = norm2(seg(:, 2) - seg(:, 1))
    ok = length > 2.0_dp*inset_m
    if (.not. ok .or. inset_m == 0.0_dp) return
    t = (seg(:, 2) - seg(:, 1))/length
    seg(:, 1) = seg(:, 1) + inset_m*t
    seg(:, 2) = seg(:, 2) - inset_m*t
  end subroutine set_in

  pure subroutine grow(body, ends, normal, cap)
    integer, allocatable, intent(inout) :: body(:, :)
    real(dp), allocatable, intent(inout) :: ends(:, :, :), normal(:, :)
    integer, intent(inout) :: cap
    integer, allocatable :: b2(:, :)
    real(dp), allocatable :: e2(:, :, :), n2(:, :)
    allocate (b2(2, 2*cap), e2(2, 2, 2*cap), n2(2, 2*cap))
    b2(:, 1:cap) = body
    e2(:, :, 1:cap) = ends
    n2(:, 1:cap) = normal
    call move_alloc(b2, body)
    call move_alloc(e2, ends)
    call move_alloc(n2, normal)
    cap = 2*cap
  end subroutine grow

end module voussoir_block_interfaces
