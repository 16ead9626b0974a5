!> The minimum thickness of a symmetric arch of chord-faced voussoirs under its own
!> weight, by the line of thrust (the static side of the limit analysis).
module voussoir_minimum_thickness
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_geometry, only: polygon_area, polygon_centroid, cross2
  use voussoir_assembly, only: assembly_t, build_arch
  use voussoir_hinge_side, only: side_intrados, side_extrados
  implicit none
  private

  public :: minimum_thickness

  !> Slack [fraction of total weight x radius] under which a joint end counts as a hinge
  !> of the minimum-thickness thrust line.
  real(dp), parameter :: hinge_slack_rel_tol = 1.0e-8_dp

  !> The arches compared in the search: all but the thickness.
  type :: arch_family_t
    real(dp) :: embrace_deg = 0.0_dp   !! total angle of embrace [deg]
    integer :: n_voussoirs = 0
    real(dp) :: r_ext_m = 0.0_dp       !! extrados radius [m]
    real(dp) :: inset_m = 0.0_dp       !! pivot distance from the joint ends [m]
  end type arch_family_t

contains

  !> Minimum thickness of a symmetric arch of `n_voussoirs` chord-faced voussoirs under
  !> its own weight (geometry of `build_arch`, same extrados radius for every trial).
  !>
  !> At the minimum thickness a symmetric line of thrust just fits: with the springing
  !> reaction (H, W/2) and its moment M0 about the centre, each joint bounds M0 linearly
  !> in H (resultant on the intrados side of the extrados pivot and on the extrados side
  !> of the intrados pivot). The thickness is bisected on the largest width of the
  !> feasible M0 interval over H (a concave function of H, maximised by golden section).
  !> The hinges are the pivots the thrust line touches, normally five (the crown, the
  !> haunches and the springings) for an even number of voussoirs and six for an odd one.
  subroutine minimum_thickness(embrace_deg, n_voussoirs, r_ext_m, inset_m, ratio_ext, ratio_mean, &
                               hinges, sides, status)
    real(dp), intent(in) :: embrace_deg      !! total angle of embrace, 0 < embrace_deg <= 180
    integer, intent(in) :: n_voussoirs       !! number of voussoirs, >= 4
    real(dp), intent(in) :: r_ext_m          !! extrados radius [m]
    real(dp), intent(in) :: inset_m          !! pivot distance from the joint ends [m]
    real(dp), intent(out) :: ratio_ext       !! minimum thickness / extrados radius
    real(dp), intent(out) :: ratio_mean      !! minimum thickness / mean radius (r_ext - t/2)
    integer, allocatable, intent(out) :: hinges(:)  !! joints of the hinges (0..n), ascending
    integer, allocatable, intent(out) :: sides(:)   !! their sides (`side_intrados` / `side_extrados`)
    type(status_t), intent(inout) :: status
    type(arch_family_t) :: family
    real(dp) :: t_lo, t_hi, t_mid, margin, h_best, m0_best
    integer :: iter
    integer, parameter :: max_bisections = 200

    ratio_ext = 0.0_dp
    ratio_mean = 0.0_dp
    allocate (hinges(0), sides(0))
    family = arch_family_t(embrace_deg, n_voussoirs, r_ext_m, inset_m)
    call check_family(family, status)
    if (.not. status%ok) return

    ! The joints must be longer than two insets; the intrados radius must stay positive.
    t_lo = 2.0_dp*inset_m + 1.0e-9_dp*r_ext_m
    t_hi = (1.0_dp - 1.0e-6_dp)*r_ext_m
    call thrust_margin(family, t_hi, margin, h_best, m0_best)
    if (margin < 0.0_dp) then
      call fail(status, 'minimum thickness: no thickness below the extrados radius carries the arch')
      return
    end if
    call thrust_margin(family, t_lo, margin, h_best, m0_best)
    if (margin >= 0.0_dp) then
      call fail(status, 'minimum thickness: the arch stands at every thickness down to twice the inset')
      return
    end if
    do iter = 1, max_bisections
      if (t_hi - t_lo <= 1.0e-14_dp*r_ext_m) exit
      t_mid = 0.5_dp*(t_lo + t_hi)
      call thrust_margin(family, t_mid, margin, h_best, m0_best)
      if (margin >= 0.0_dp) then
        t_hi = t_mid
      else
        t_lo = t_mid
      end if
    end do
    ratio_ext = t_hi/r_ext_m
    ratio_mean = t_hi/(r_ext_m - 0.5_dp*t_hi)
    call touching_pivots(family, t_hi, hinges, sides)
  end subroutine minimum_thickness

  !> The family's values are in range (the messages name the argument and its range).
  subroutine check_family(family, status)
    type(arch_family_t), intent(in) :: family
    type(status_t), intent(inout) :: status
    if (.not. (family%embrace_deg > 0.0_dp .and. family%embrace_deg <= 180.0_dp)) then
      call fail(status, 'minimum thickness: embrace_deg must satisfy 0 < embrace_deg <= 180')
    else if (family%n_voussoirs < 4) then
      call fail(status, 'minimum thickness: n_voussoirs must be >= 4 (an arch of 3 voussoirs stands '// &
                'at vanishing thickness)')
    else if (.not. (family%r_ext_m > 0.0_dp)) then
      call fail(status, 'minimum thickness: r_ext_m must be > 0')
    else if (.not. (family%inset_m >= 0.0_dp .and. family%inset_m < 0.25_dp*family%r_ext_m)) then
      call fail(status, 'minimum thickness: inset_m must satisfy 0 <= inset_m < r_ext_m / 4')
    end if
  end subroutine check_family

  !> Pivots, springing reaction factors and load sums of the arch of `family` of thickness t_m.
  subroutine symmetric_terms(family, t_m, p_int, p_ext, share, wx_sum, w_total)
    type(arch_family_t), intent(in) :: family
    real(dp), intent(in) :: t_m
    real(dp), intent(out) :: p_int(2, 0:family%n_voussoirs), p_ext(2, 0:family%n_voussoirs)
    real(dp), intent(out) :: share(0:family%n_voussoirs), wx_sum(0:family%n_voussoirs), w_total
    type(assembly_t) :: arch
    real(dp) :: e(2), w_sum(0:family%n_voussoirs), area, c(2)
    integer :: j, n

    n = family%n_voussoirs
    call build_arch(family%embrace_deg, n, family%r_ext_m, t_m, arch)
    w_sum(0) = 0.0_dp
    wx_sum(0) = 0.0_dp
    do j = 1, n
      area = polygon_area(arch%polygon(j)%xy)
      c = polygon_centroid(arch%polygon(j)%xy)
      w_sum(j) = w_sum(j - 1) + area
      wx_sum(j) = wx_sum(j - 1) + area*c(1)
    end do
    w_total = w_sum(n)
    ! Vertical component of the joint resultant: half the weight minus the blocks to its left.
    share = 0.5_dp*w_total - w_sum
    do j = 0, n
      e = arch%joint_extrados_xy(:, j) - arch%joint_intrados_xy(:, j)
      e = e/norm2(e)
      p_int(:, j) = arch%joint_intrados_xy(:, j) + family%inset_m*e
      p_ext(:, j) = arch%joint_extrados_xy(:, j) - family%inset_m*e
    end do
  end subroutine symmetric_terms

  !> Width of the admissible M0 interval at horizontal thrust h (negative if empty).
  pure real(dp) function interval_width(h, p_int, p_ext, share, wx_sum)
    real(dp), intent(in) :: h, p_int(:, 0:), p_ext(:, 0:)
    real(dp), intent(in) :: share(0:), wx_sum(0:)
    interval_width = minval(p_int(1, :)*share - p_int(2, :)*h + wx_sum) &
                     - maxval(p_ext(1, :)*share - p_ext(2, :)*h + wx_sum)
  end function interval_width

  !> Largest interval width over h >= 0 at thickness t_m, its h and the mid M0.
  subroutine thrust_margin(family, t_m, margin, h_best, m0_mid)
    type(arch_family_t), intent(in) :: family
    real(dp), intent(in) :: t_m
    real(dp), intent(out) :: margin, h_best, m0_mid
    real(dp) :: p_int(2, 0:family%n_voussoirs), p_ext(2, 0:family%n_voussoirs), share(0:family%n_voussoirs)
    real(dp) :: wx_sum(0:family%n_voussoirs), w_total, h_lo, h_hi, h1, h2, f1, f2
    real(dp), parameter :: golden = 0.6180339887498949_dp
    integer :: k

    call symmetric_terms(family, t_m, p_int, p_ext, share, wx_sum, w_total)
    ! Bracket the maximiser of the concave width: it lies below h_hi once the width drops.
    h_hi = w_total
    do k = 1, 200
      if (interval_width(h_hi, p_int, p_ext, share, wx_sum) &
          < interval_width(0.5_dp*h_hi, p_int, p_ext, share, wx_sum)) exit
      h_hi = 2.0_dp*h_hi
    end do
    h_lo = 0.0_dp
    h1 = h_hi - golden*(h_hi - h_lo)
    h2 = h_lo + golden*(h_hi - h_lo)
    f1 = interval_width(h1, p_int, p_ext, share, wx_sum)
    f2 = interval_width(h2, p_int, p_ext, share, wx_sum)
    do k = 1, 300
      if (h_hi - h_lo <= 1.0e-15_dp*h_hi) exit
      if (f1 < f2) then
        h_lo = h1
        h1 = h2
        f1 = f2
        h2 = h_lo + golden*(h_hi - h_lo)
        f2 = interval_width(h2, p_int, p_ext, share, wx_sum)
      else
        h_hi = h2
        h2 = h1
        f2 = f1
        h1 = h_hi - golden*(h_hi - h_lo)
        f1 = interval_width(h1, p_int, p_ext, share, wx_sum)
      end if
    end do
    h_best = 0.5_dp*(h_lo + h_hi)
    margin = interval_width(h_best, p_int, p_ext, share, wx_sum)
    m0_mid = 0.5_dp*(minval(p_int(1, :)*share - p_int(2, :)*h_best + wx_sum) &
                     + maxval(p_ext(1, :)*share - p_ext(2, :)*h_best + wx_sum))
  end subroutine thrust_margin

  !> The pivots that the just-fitting thrust line at thickness t_m touches, added to
  !> `hinges` and `sides` in joint order.
  subroutine touching_pivots(family, t_m, hinges, sides)
    type(arch_family_t), intent(in) :: family
    real(dp), intent(in) :: t_m
    integer, allocatable, intent(inout) :: hinges(:), sides(:)
    real(dp) :: p_int(2, 0:family%n_voussoirs), p_ext(2, 0:family%n_voussoirs), share(0:family%n_voussoirs)
    real(dp) :: wx_sum(0:family%n_voussoirs), w_total, margin, h_best, m0_mid, slack_tol
    integer :: j

    call thrust_margin(family, t_m, margin, h_best, m0_mid)
    call symmetric_terms(family, t_m, p_int, p_ext, share, wx_sum, w_total)
    slack_tol = hinge_slack_rel_tol*w_total*family%r_ext_m
    do j = 0, family%n_voussoirs
      if (p_int(1, j)*share(j) - p_int(2, j)*h_best + wx_sum(j) - m0_mid <= slack_tol) then
        hinges = [hinges, j]
        sides = [sides, side_intrados]
      end if
      if (m0_mid - (p_ext(1, j)*share(j) - p_ext(2, j)*h_best + wx_sum(j)) <= slack_tol) then
        hinges = [hinges, j]
        sides = [sides, side_extrados]
      end if
    end do
  end subroutine touching_pivots

end module voussoir_minimum_thickness
