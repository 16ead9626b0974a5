!> A stable order of rows by keys: the scheduler's queue of jobs and the result tables
!> both sort with it.
module voussoir_ordering
  use voussoir_kinds, only: dp
  implicit none
  private

  public :: stable_order

contains

  !> The permutation that sorts the columns of `keys` (one row per key, compared in
  !> order) ascending; equal columns keep their order (bottom-up merge sort).
  pure function stable_order(keys) result(order)
    real(dp), intent(in) :: keys(:, :)   !! (n_keys, n)
    integer, allocatable :: order(:)
    integer, allocatable :: tmp(:)
    integer :: n, width, lo, mid, hi, i, j, m
    n = size(keys, 2)
    order = [(i, i=1, n)]
    if (n < 2) return
    allocate (tmp(n))
    width = 1
    do while (width < n)
      lo = 1
      do while (lo <= n)
        mid = min(lo + width - 1, n)
        hi = min(lo + 2*width - 1, n)
        i = lo
        j = mid + 1
        m = lo
        do while (i <= mid .and. j <= hi)
          if (before(order(j), order(i))) then
            tmp(m) = order(j)
            j = j + 1
          else
            tmp(m) = order(i)
            i = i + 1
          end if
          m = m + 1
        end do
        tmp(m:m + mid - i) = order(i:mid)
        m = m + mid - i + 1
        tmp(m:m + hi - j) = order(j:hi)
        order(lo:hi) = tmp(lo:hi)
        lo = lo + 2*width
      end do
      width = 2*width
    end do
  contains
    !> Column a strictly before column b.
    pure logical function before(a, b)
      integer, intent(in) :: a, b
      integer :: q
      before = .false.
      do q = 1, size(keys, 1)
        if (keys(q, a) < keys(q, b)) then
          before = .true.
          return
        else if (keys(q, a) > keys(q, b)) then
          return
        end if
      end do
    end function before
  end function stable_order

end module voussoir_ordering
