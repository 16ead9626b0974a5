!> When a run need not solve its steps: an assembly at rest on the table, loaded below its
!> static capacity lambda g, moves with the table (the lower-bound theorem of limit
!> analysis: a statically admissible field carries the load, so rest is a solution of
!> every step). A record run (the IDA's) spends most of its steps so: before the strong
!> motion, and after it once the blocks have settled.
!>
!> Two windows of steps, from the table's acceleration alone:
!>  - the lead: the steps before the table's |a| first reaches `lead_fraction` of the
!>    capacity; the assembly, at rest as built, rides on the table (not solved);
!>  - the tail: the steps after the last |a| above `tail_fraction` of the capacity; there
!>    the run ends once every free block has been still on the table (relative speed below
!>    `still_speed_m_s`) for `still_s` and none has moved from where it was built by more
!>    than `drift_fraction` of its size (a block that slid or rocked to a new place has a
!>    capacity of its own, which the margin of `tail_fraction` covers only for small
!>    moves): it stands.
!> The margins (0.9 and 0.5 of the capacity) keep the windows clear of the NLGS's
!> tolerance and of the small residual moves of a rocked arch.
module voussoir_rest_window
  use voussoir_kinds, only: dp
  use voussoir_bodies, only: bodies_t
  use voussoir_motion, only: motion_t, motion_eval
  implicit none
  private

  public :: rest_window_t, rest_window, relative_speed, smallest_free_size

  real(dp), parameter, public :: lead_fraction = 0.9_dp
  real(dp), parameter, public :: tail_fraction = 0.5_dp
  real(dp), parameter, public :: still_speed_m_s = 1.0e-4_dp
  real(dp), parameter, public :: still_s = 0.25_dp
  real(dp), parameter, public :: drift_fraction = 0.05_dp

  !> The windows of a run of `n_steps` steps: steps 1 .. lead_steps ride on the table;
  !> after step tail_step the run may end at rest. Without a capacity: no lead, no tail.
  type :: rest_window_t
    integer :: lead_steps = 0
    integer :: tail_step = huge(1)
  end type rest_window_t

contains

  !> The windows of the table motion `motion` over `n_steps` steps of `dt_s` for an
  !> assembly of static capacity `capacity_m_s2` (lambda g; 0: none).
  pure function rest_window(motion, dt_s, n_steps, capacity_m_s2) result(w)
    type(motion_t), intent(in) :: motion
    real(dp), intent(in) :: dt_s, capacity_m_s2
    integer, intent(in) :: n_steps
    type(rest_window_t) :: w
    real(dp) :: x, v, a
    integer :: k
    logical :: lead_open
    if (.not. capacity_m_s2 > 0.0_dp) return
    lead_open = .true.
    w%tail_step = 0
    do k = 0, n_steps
      call motion_eval(motion, k*dt_s, x, v, a)
      if (lead_open .and. abs(a) >= lead_fraction*capacity_m_s2) then
        lead_open = .false.
        w%lead_steps = max(0, k - 1)
      end if
      if (abs(a) >= tail_fraction*capacity_m_s2) w%tail_step = k
    end do
    if (lead_open) w%lead_steps = n_steps
  end function rest_window

  !> The largest speed of a point of a free body relative to the table moving at
  !> `v_table_m_s` along x [m/s] (a rotation counted at the body's farthest vertex).
  pure real(dp) function relative_speed(bodies, v_table_m_s) result(speed)
    type(bodies_t), intent(in) :: bodies
    real(dp), intent(in) :: v_table_m_s
    integer :: i
    speed = 0.0_dp
    do i = 1, bodies%n
      if (bodies%driven(i)) cycle
      speed = max(speed, abs(bodies%v(1, i) - v_table_m_s), abs(bodies%v(2, i)), &
                  abs(bodies%v(3, i))*bodies%radius_m(i))
    end do
  end function relative_speed

  !> The size (farthest vertex from the centroid) of the smallest free body [m].
  pure real(dp) function smallest_free_size(bodies) result(size_m)
    type(bodies_t), intent(in) :: bodies
    size_m = minval(bodies%radius_m, mask=.not. bodies%driven)
  end function smallest_free_size

end module voussoir_rest_window
