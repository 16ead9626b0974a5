!> Contact detection between rigid convex polygons.
!>
!> Broad phase: axis-aligned boxes sorted into a uniform cell grid whose cell is at least
!> the largest box, so that each body meets only the bodies of its 3 x 3 cells and the
!> cost grows linearly with the number of bodies. Narrow phase: the face of largest
!> separation (separating-axis test) is the reference face of the antagonist body; the
!> most opposed face of the candidate body is clipped to it, and the two ends of the
!> overlap (set in by the contact inset) are the contact points.
module voussoir_contacts
  use voussoir_kinds, only: dp
  use voussoir_geometry, only: cross2
  use voussoir_bodies, only: bodies_t
  use voussoir_contact_law, only: contact_law_t, pair_friction_of
  implicit none
  private

  public :: contact_set_t, detect_contacts, polygon_contact, relative_motion_m

  !> The contact points of one step, structure of arrays. Body `a` is the candidate,
  !> body `b` the antagonist that owns the reference face; the normal points from b to a.
  type :: contact_set_t
    integer :: n = 0
    integer, allocatable :: body_a(:), body_b(:), slot(:)
    real(dp), allocatable :: normal(:, :), tangent(:, :) !! (2, n) unit vectors
    real(dp), allocatable :: arm_a(:, :), arm_b(:, :)    !! (2, n) centroid -> point [m]
    real(dp), allocatable :: point(:, :)                 !! (2, n) contact point [m]
    real(dp), allocatable :: gap_m(:)
    real(dp), allocatable :: friction(:)
    real(dp), allocatable :: impulse(:, :)               !! (2, n) [N s], (tangent, normal)
    ! The broad phase's pair list, the configuration it was built for, and its work arrays.
    integer :: n_pairs = 0
    integer, allocatable :: pairs(:, :)
    real(dp), allocatable :: q_pairs(:, :)
    integer, allocatable :: cell_start(:), cell_body(:), body_cell(:, :)
  end type contact_set_t

contains

  !> Make room for at least `capacity` contacts, keeping the `set%n` present.
  subroutine reserve(set, capacity)
    type(contact_set_t), intent(inout) :: set
    integer, intent(in) :: capacity
    integer :: new_cap
    if (allocated(set%body_a)) then
      if (size(set%body_a) >= capacity) return
    end if
    new_cap = max(64, 2*capacity)
    call grow_int(set%body_a, set%n, new_cap)
    call grow_int(set%body_b, set%n, new_cap)
    call grow_int(set%slot, set%n, new_cap)
    call grow_real2(set%normal, set%n, new_cap)
    call grow_real2(set%tangent, set%n, new_cap)
    call grow_real2(set%arm_a, set%n, new_cap)
    call grow_real2(set%arm_b, set%n, new_cap)
    call grow_real2(set%point, set%n, new_cap)
    call grow_real2(set%impulse, set%n, new_cap)
    call grow_real(set%gap_m, set%n, new_cap)
    call grow_real(set%friction, set%n, new_cap)
  end subroutine reserve

  !> `a` with room for `capacity` entries, its first `n_keep` kept (none if unallocated).
  pure subroutine grow_int(a, n_keep, capacity)
    integer, allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n_keep, capacity
    integer, allocatable :: b(:)
    allocate (b(capacity))
    if (allocated(a)) b(1:n_keep) = a(1:n_keep)
    call move_alloc(b, a)
  end subroutine grow_int

  !> `a` with room for `capacity` entries, its first `n_keep` kept (none if unallocated).
  pure subroutine grow_real(a, n_keep, capacity)
    real(dp), allocatable, intent(inout) :: a(:)
    integer, intent(in) :: n_keep, capacity
    real(dp), allocatable :: b(:)
    allocate (b(capacity))
    if (allocated(a)) b(1:n_keep) = a(1:n_keep)
    call move_alloc(b, a)
  end subroutine grow_real

  !> `a` (2, :) with room for `capacity` columns, its first `n_keep` kept (none if unallocated).
  pure subroutine grow_real2(a, n_keep, capacity)
    real(dp), allocatable, intent(inout) :: a(:, :)
    integer, intent(in) :: n_keep, capacity
    real(dp), allocatable :: b(:, :)
    allocate (b(2, capacity))
    if (allocated(a)) b(:, 1:n_keep) = a(:, 1:n_keep)
    call move_alloc(b, a)
  end subroutine grow_real2

  !> All contact points within `alert_m` for the current world vertices of `bodies`
  !> (the caller has set them to the predicted configuration `q`).
  !>
  !> The broad phase keeps a list of the pairs whose boxes, grown by `alert_m` plus a
  !> margin of `alert_m`, overlap (a Verlet list); it is rebuilt only once some body has
  !> moved by more than half the margin since, apart from a translation common to all
  !> (the table carries the whole assembly; relative_motion_m), so most steps run the
  !> narrow phase only.
  subroutine detect_contacts(bodies, q, alert_m, law, set)
    type(bodies_t), intent(in) :: bodies
    real(dp), intent(in) :: q(:, :)           !! (3, n) configuration of the vertices
    real(dp), intent(in) :: alert_m
    type(contact_law_t), intent(in) :: law
    type(contact_set_t), intent(inout) :: set
    integer :: p, nb
    real(dp) :: moved_m

    nb = bodies%n
    set%n = 0
    if (.not. allocated(set%q_pairs)) then
      moved_m = huge(1.0_dp)
    else if (size(set%q_pairs, 2) /= nb) then
      moved_m = huge(1.0_dp)
    else
      moved_m = relative_motion_m(q, set%q_pairs, bodies%radius_m)
    end if
    if (moved_m > 0.5_dp*alert_m) then
      call broad_phase(bodies, 2.0_dp*alert_m, set)
      set%q_pairs = q
    end if
    ! Room for two points per pair once, not a test per pair.
    call reserve(set, 2*set%n_pairs)
    do p = 1, set%n_pairs
      call add_pair(bodies, q, alert_m, law, set%pairs(1, p), set%pairs(2, p), set)
    end do
  end subroutine detect_contacts

  !> The contact points of bodies i and j within `alert_m` in the configuration `q`
  !> (3, n), added to `set` (none when the polygons are apart).
  subroutine add_pair(bodies, q, alert_m, law, i, j, set)
    type(bodies_t), intent(in) :: bodies
    real(dp), intent(in) :: q(:, :), alert_m
    type(contact_law_t), intent(in) :: law
    integer, intent(in) :: i, j
    type(contact_set_t), intent(inout) :: set
    integer :: n_points, a, b, p, m
    real(dp) :: points(2, 2), gaps(2), normal(2)
    logical :: i_is_candidate
    real(dp) :: mu

    associate (ni => bodies%n_vertices(i), nj => bodies%n_vertices(j))
      call polygon_contact_normals(bodies%vertex(:, 1:ni, i), bodies%face_normal(:, 1:ni, i), &
                                   bodies%vertex(:, 1:nj, j), bodies%face_normal(:, 1:nj, j), &
                                   alert_m, law%inset_m, n_points, points, gaps, normal, i_is_candidate)
    end associate
    if (n_points == 0) return
    if (i_is_candidate) then
      a = i
      b = j
    else
      a = j
      b = i
    end if
    mu = pair_friction_of(law, a, b)
    do p = 1, 2
      if (gaps(p) > alert_m) cycle
      if (p == 2 .and. n_points == 1) cycle
      set%n = set%n + 1
      m = set%n
      set%body_a(m) = a
      set%body_b(m) = b
      set%slot(m) = p
      ! Element by element: two-element array assignments compile to library calls.
      set%normal(1, m) = normal(1)
      set%normal(2, m) = normal(2)
      set%tangent(1, m) = -normal(2)
      set%tangent(2, m) = normal(1)
      set%point(1, m) = points(1, p)
      set%point(2, m) = points(2, p)
      set%arm_a(1, m) = points(1, p) - q(1, a)
      set%arm_a(2, m) = points(2, p) - q(2, a)
      set%arm_b(1, m) = points(1, p) - q(1, b)
      set%arm_b(2, m) = points(2, p) - q(2, b)
      set%gap_m(m) = gaps(p)
      set%friction(m) = mu
      set%impulse(1, m) = 0.0_dp
      set%impulse(2, m) = 0.0_dp
    end do
  end subroutine add_pair

  !> The largest motion of a body from `q_ref` to `q` (3, n) apart from a translation
  !> common to all bodies: |dx - cx| + |dy - cy| + radius |d theta| [m], (cx, cy) the
  !> middle of the range of the displacements. No vertex of a body has moved by more
  !> than that relative to the common translation, so the distance between two bodies
  !> has changed by at most the sum of their two motions so measured.
  pure function relative_motion_m(q, q_ref, radius_m) result(moved_m)
    real(dp), intent(in) :: q(:, :), q_ref(:, :), radius_m(:)
    real(dp) :: moved_m, lo(2), hi(2), common(2)
    integer :: i

    lo = huge(1.0_dp)
    hi = -huge(1.0_dp)
    do i = 1, size(q, 2)
      lo = min(lo, q(1:2, i) - q_ref(1:2, i))
      hi = max(hi, q(1:2, i) - q_ref(1:2, i))
    end do
    common = 0.5_dp*(lo + hi)
    moved_m = 0.0_dp
    do i = 1, size(q, 2)
      moved_m = max(moved_m, abs(q(1, i) - q_ref(1, i) - common(1)) + abs(q(2, i) - q_ref(2, i) - common(2)) &
                             + radius_m(i)*abs(q(3, i) - q_ref(3, i)))
    end do
  end function relative_motion_m

  !> Pairs of bodies (not both driven) whose boxes grown by `reach_m` overlap, found
  !> with a uniform cell grid whose cell is at least the largest box.
  subroutine broad_phase(bodies, reach_m, set)
    type(bodies_t), intent(in) :: bodies
    real(dp), intent(in) :: reach_m
    type(contact_set_t), intent(inout) :: set
    real(dp) :: box(4, bodies%n), lo(2), cell_m
    integer :: nx, ny, i, j, ix, iy, jx, jy, c, k, nb, n_cells

    nb = bodies%n
    set%n_pairs = 0
    do i = 1, nb
      associate (vx => bodies%vertex(1, 1:bodies%n_vertices(i), i), &
                 vy => bodies%vertex(2, 1:bodies%n_vertices(i), i))
        box(:, i) = [minval(vx), minval(vy), maxval(vx), maxval(vy)] &
                    + [-0.5_dp, -0.5_dp, 0.5_dp, 0.5_dp]*reach_m
      end associate
    end do
    lo = [minval(box(1, :)), minval(box(2, :))]
    cell_m = max(maxval(box(3, :) - box(1, :)), maxval(box(4, :) - box(2, :)))
    nx = max(1, min(int((maxval(box(3, :)) - lo(1))/cell_m) + 1, 4*nb))
    ny = max(1, min(int((maxval(box(4, :)) - lo(2))/cell_m) + 1, 4*nb))
    cell_m = max(cell_m, (maxval(box(3, :)) - lo(1))/nx, (maxval(box(4, :)) - lo(2))/ny)
    n_cells = nx*ny

    ! Counting sort of bodies into the cell of their box's lower corner.
    if (.not. allocated(set%cell_start)) then
      allocate (set%cell_start(n_cells + 1), set%cell_body(nb), set%body_cell(2, nb))
    else if (size(set%cell_start) < n_cells + 1 .or. size(set%cell_body) < nb) then
      deallocate (set%cell_start, set%cell_body, set%body_cell)
      allocate (set%cell_start(n_cells + 1), set%cell_body(nb), set%body_cell(2, nb))
    end if
    set%cell_start(1:n_cells + 1) = 0
    do i = 1, nb
      ix = min(nx - 1, int((box(1, i) - lo(1))/cell_m))
      iy = min(ny - 1, int((box(2, i) - lo(2))/cell_m))
      set%body_cell(:, i) = [ix, iy]
      c = ix + nx*iy + 2
      set%cell_start(c) = set%cell_start(c) + 1
    end do
    set%cell_start(1) = 1
    do c = 2, n_cells + 1
      set%cell_start(c) = set%cell_start(c) + set%cell_start(c - 1)
    end do
    ! Cell c will hold cell_body(cell_start(c) : cell_start(c+1)-1); fill from the top,
    ! which leaves the start of cell c in cell_start(c+1).
    do i = nb, 1, -1
      c = set%body_cell(1, i) + nx*set%body_cell(2, i) + 1
      set%cell_start(c + 1) = set%cell_start(c + 1) - 1
      set%cell_body(set%cell_start(c + 1)) = i
    end do
    ! Shift back so that cell c starts at cell_start(c).
    do c = 1, n_cells
      set%cell_start(c) = set%cell_start(c + 1)
    end do
    set%cell_start(n_cells + 1) = nb + 1

    do i = 1, nb
      ix = set%body_cell(1, i)
      iy = set%body_cell(2, i)
      do jy = max(0, iy - 1), min(ny - 1, iy + 1)
        do jx = max(0, ix - 1), min(nx - 1, ix + 1)
          c = jx + nx*jy + 1
          do k = set%cell_start(c), set%cell_start(c + 1) - 1
            j = set%cell_body(k)
            if (j == i) cycle
            if (bodies%driven(i) .and. bodies%driven(j)) cycle
            if (box(1, i) > box(3, j) .or. box(1, j) > box(3, i)) cycle
            if (box(2, i) > box(4, j) .or. box(2, j) > box(4, i)) cycle
            if (j < i) cycle
            call push_pair(set, min(i, j), max(i, j), nb)
          end do
        end do
      end do
    end do
  end subroutine broad_phase

  !> Add the pair (i, j) to the broad phase's list of `set`, growing it as needed (its
  !> first size 4 nb + 16 for `nb` bodies).
  pure subroutine push_pair(set, i, j, nb)
    type(contact_set_t), intent(inout) :: set
    integer, intent(in) :: i, j, nb
    integer, allocatable :: grown(:, :)
    if (.not. allocated(set%pairs)) allocate (set%pairs(2, 4*nb + 16))
    if (set%n_pairs == size(set%pairs, 2)) then
      allocate (grown(2, 2*size(set%pairs, 2)))
      grown(:, 1:set%n_pairs) = set%pairs(:, 1:set%n_pairs)
      call move_alloc(grown, set%pairs)
    end if
    set%n_pairs = set%n_pairs + 1
    set%pairs(:, set%n_pairs) = [i, j]
  end subroutine push_pair

  !> Face-to-face contact of two convex polygons `pa`, `pb` (2, n) counter-clockwise.
  !>
  !> Returns up to two points on the candidate's incident face, their gaps [m] along the
  !> reference face's outward normal (pointing from the antagonist to the candidate),
  !> and whether `pa` is the candidate. The points are the ends of the part of the
  !> incident face that lies over the reference face, each moved inwards by `inset_m`
  !> (merged into one point when the overlap is shorter than two insets).
  pure subroutine polygon_contact(pa, pb, alert_m, inset_m, n_points, points, gaps, normal, &
                                  a_is_candidate)
    real(dp), intent(in) :: pa(:, :), pb(:, :), alert_m, inset_m
    integer, intent(out) :: n_points
    real(dp), intent(out) :: points(2, 2), gaps(2), normal(2)
    logical, intent(out) :: a_is_candidate
    real(dp), allocatable :: na(:, :), nb(:, :)
    allocate (na(2, size(pa, 2)), nb(2, size(pb, 2)))
    call face_normals(pa, na)
    call face_normals(pb, nb)
    call polygon_contact_normals(pa, na, pb, nb, alert_m, inset_m, n_points, points, gaps, normal, &
                                 a_is_candidate)
  end subroutine polygon_contact

  !> `polygon_contact` with the outward unit normals of the faces given (face k runs
  !> from vertex k to vertex k+1).
  pure subroutine polygon_contact_normals(pa, na, pb, nb, alert_m, inset_m, n_points, points, gaps, &
                                          normal, a_is_candidate)
    real(dp), intent(in), contiguous :: pa(:, :), na(:, :), pb(:, :), nb(:, :)
    real(dp), intent(in) :: alert_m, inset_m
    integer, intent(out) :: n_points
    real(dp), intent(out) :: points(2, 2), gaps(2), normal(2)
    logical, intent(out) :: a_is_candidate
    real(dp) :: sep_a, sep_b
    integer :: face_a, face_b

    n_points = 0
    points = 0.0_dp
    gaps = huge(1.0_dp)
    normal = 0.0_dp
    a_is_candidate = .true.
    call max_separation(pa, na, pb, alert_m, sep_a, face_a)
    if (sep_a > alert_m) return
    call max_separation(pb, nb, pa, alert_m, sep_b, face_b)
    if (sep_b > alert_m) return
    ! Prefer the face of b as reference unless a's face separates clearly more, so that
    ! the choice does not flip between parallel faces from one step to the next.
    if (sep_a > sep_b + 1.0e-3_dp*alert_m) then
      a_is_candidate = .false.
      call clip(pb, nb, pa, na, face_a, inset_m, n_points, points, gaps, normal)
    else
      call clip(pa, na, pb, nb, face_b, inset_m, n_points, points, gaps, normal)
    end if
  end subroutine polygon_contact_normals

  !> Contact points of the incident face of `cand` (outward unit face normals
  !> `cand_normals`) on face `ref_face` of `ref`.
  pure subroutine clip(cand, cand_normals, ref, ref_normals, ref_face, inset_m, n_points, points, gaps, normal)
    real(dp), intent(in), contiguous :: cand(:, :), cand_normals(:, :), ref(:, :), ref_normals(:, :)
    real(dp), intent(in) :: inset_m
    integer, intent(in) :: ref_face
    integer, intent(inout) :: n_points
    real(dp), intent(inout) :: points(2, 2), gaps(2), normal(2)
    real(dp) :: r1(2), r2(2), t(2), len_ref, d, best, s1, s2, s_lo, s_hi, c1(2), c2(2), &
                e(2), len_inc, u_lo, u_hi, mid
    integer :: k, inc, nc, nr

    nr = size(ref, 2)
    nc = size(cand, 2)
    r1 = ref(:, ref_face)
    r2 = ref(:, next_vertex(ref_face, nr))
    normal = ref_normals(:, ref_face)
    t = [-normal(2), normal(1)]
    len_ref = dot_product(r2 - r1, t)
    ! Incident face: the candidate's face most opposed to the normal (its stored unit
    ! normal, not one recomputed from the edge: only the choice of face is used).
    best = huge(1.0_dp)
    inc = 1
    do k = 1, nc
      d = normal(1)*cand_normals(1, k) + normal(2)*cand_normals(2, k)
      if (d < best) then
        best = d
        inc = k
      end if
    end do
    c1 = cand(:, inc)
    c2 = cand(:, next_vertex(inc, nc))
    ! Parametrise the incident face by its projection on the reference tangent.
    s1 = dot_product(c1 - r1, t)
    s2 = dot_product(c2 - r1, t)
    if (abs(s2 - s1) < tiny(1.0_dp)) return
    s_lo = max(min(s1, s2), 0.0_dp)
    s_hi = min(max(s1, s2), len_ref)
    if (s_hi < s_lo) return
    len_inc = norm2(c2 - c1)
    ! Curvilinear abscissae along the incident face of the overlap ends.
    u_lo = (s_lo - s1)/(s2 - s1)*len_inc
    u_hi = (s_hi - s1)/(s2 - s1)*len_inc
    if (u_lo > u_hi) then
      mid = u_lo
      u_lo = u_hi
      u_hi = mid
    end if
    if (u_hi - u_lo > 2.0_dp*inset_m) then
      u_lo = u_lo + inset_m
      u_hi = u_hi - inset_m
      n_points = 2
    else
      u_lo = 0.5_dp*(u_lo + u_hi)
      u_hi = u_lo
      n_points = 1
    end if
    e = (c2 - c1)/len_inc
    points(:, 1) = c1 + u_lo*e
    points(:, 2) = c1 + u_hi*e
    gaps(1) = dot_product(points(:, 1) - r1, normal)
    gaps(2) = dot_product(points(:, 2) - r1, normal)
  end subroutine clip

  !> The vertex after vertex `k` of a polygon of `n` vertices (without an integer division).
  pure integer function next_vertex(k, n)
    integer, intent(in) :: k, n
    next_vertex = k + 1
    if (k == n) next_vertex = 1
  end function next_vertex

  !> Outward unit normals of the faces of a counter-clockwise polygon.
  pure subroutine face_normals(p, normals)
    real(dp), intent(in) :: p(:, :)
    real(dp), intent(out) :: normals(:, :)
    real(dp) :: e(2)
    integer :: i, np
    np = size(p, 2)
    do i = 1, np
      e = p(:, modulo(i, np) + 1) - p(:, i)
      normals(:, i) = [e(2), -e(1)]/norm2(e)
    end do
  end subroutine face_normals

  !> Largest separation of `q`'s vertices from a face of `p` (separating-axis test):
  !> for every face of p, the smallest signed distance of q's vertices along the face's
  !> outward normal; the largest of these over p's faces, and that face. Stops as soon
  !> as a face separates by more than `alert_m`. A face is left as soon as one vertex
  !> of q is no further than the best separation so far (the face cannot beat it), so
  !> the result is that of the full search.
  pure subroutine max_separation(p, normals, q, alert_m, separation, face)
    real(dp), intent(in), contiguous :: p(:, :), normals(:, :), q(:, :)
    real(dp), intent(in) :: alert_m
    real(dp), intent(out) :: separation
    integer, intent(out) :: face
    real(dp) :: s
    integer :: i, k
    separation = -huge(1.0_dp)
    face = 1
    faces: do i = 1, size(p, 2)
      s = huge(1.0_dp)
      do k = 1, size(q, 2)
        s = min(s, normals(1, i)*(q(1, k) - p(1, i)) + normals(2, i)*(q(2, k) - p(2, i)))
        if (s <= separation) cycle faces
      end do
      if (s > separation) then
        separation = s
        face = i
        if (s > alert_m) return
      end if
    end do faces
  end subroutine max_separation

end module voussoir_contacts
