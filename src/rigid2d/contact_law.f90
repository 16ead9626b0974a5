!> The contact law of an assembly (the seed's inelastic quasi-shock with Coulomb
!> friction): the friction coefficient, with overrides for given pairs of bodies (the
!> joints of an arch), and the contact inset, the distance by which contact points are
!> set in from the face ends. Physics of the contacts, apart from the numerical settings
!> of the solver.
module voussoir_contact_law
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa, fmt_real
  use voussoir_assembly, only: assembly_t, between_rings
  implicit none
  private

  public :: contact_law_t, pair_friction_t, contact_law_init, pair_friction_of

  !> A friction coefficient for one pair of bodies, overriding the default.
  type :: pair_friction_t
    integer :: body_a = 0, body_b = 0
    real(dp) :: friction = 0.0_dp
  end type pair_friction_t

  !> Coulomb friction and contact inset of every contact of an assembly.
  type :: contact_law_t
    real(dp) :: friction = 0.5_dp                   !! default Coulomb coefficient
    real(dp) :: inset_m = 0.0_dp                    !! contact points set in from face ends [m]
    type(pair_friction_t), allocatable :: pairs(:)  !! overrides, e.g. per joint
    !> Each body's own coefficient, where the assembly gives them (a bridge's parts): a
    !> contact takes the lesser of its two bodies'.
    real(dp), allocatable :: body_friction(:)
    !> Each body's ring, where the assembly gives them (a multi-ring bridge): a contact
    !> between two rings takes ring_joint_friction.
    integer, allocatable :: body_ring(:)
    real(dp) :: ring_joint_friction = 0.0_dp
  end type contact_law_t

contains

  !> The law of `assembly`: `friction` everywhere except at the joints j with
  !> `joint_friction(j) >= 0` (j = 0..n of an arch, MEASURED_DATA.md numbering).
  subroutine contact_law_init(friction, inset_m, joint_friction, assembly, law, status)
    real(dp), intent(in) :: friction, inset_m
    real(dp), intent(in) :: joint_friction(0:)  !! per joint; < 0: the default
    type(assembly_t), intent(in) :: assembly
    type(contact_law_t), intent(out) :: law
    type(status_t), intent(inout) :: status
    integer :: j, n_set
    law%friction = friction
    law%inset_m = inset_m
    if (allocated(assembly%friction)) law%body_friction = assembly%friction
    if (allocated(assembly%ring)) law%body_ring = assembly%ring
    law%ring_joint_friction = assembly%ring_joint_friction
    n_set = count(joint_friction >= 0.0_dp)
    allocate (law%pairs(n_set))
    if (n_set == 0) return
    if (assembly%n_voussoirs == 0) then
      call fail(status, 'joint_friction is set, but a polygon assembly has no numbered joints')
      return
    end if
    n_set = 0
    do j = 0, ubound(joint_friction, 1)
      if (joint_friction(j) < 0.0_dp) cycle
      if (j > assembly%n_voussoirs) then
        call fail(status, 'joint_friction('//itoa(j)//') = '//fmt_real(joint_friction(j))// &
                  ': the arch has joints 0..'//itoa(assembly%n_voussoirs)//' only')
        return
      end if
      n_set = n_set + 1
      law%pairs(n_set) = pair_friction_t(assembly%joint_bodies(1, j), assembly%joint_bodies(2, j), &
                                         joint_friction(j))
    end do
  end subroutine contact_law_init

  !> The friction coefficient between bodies `a` and `b`: a joint's own where set, else the
  !> ring-to-ring coefficient between two rings of a bridge, else the lesser of the two
  !> bodies' own where the assembly gives them, else the law's.
  pure real(dp) function pair_friction_of(law, a, b) result(mu)
    type(contact_law_t), intent(in) :: law
    integer, intent(in) :: a, b
    integer :: m
    mu = law%friction
    if (allocated(law%body_friction)) mu = min(law%body_friction(a), law%body_friction(b))
    if (allocated(law%body_ring)) then
      if (between_rings(law%body_ring, a, b)) mu = law%ring_joint_friction
    end if
    do m = 1, size(law%pairs)
      if ((law%pairs(m)%body_a == a .and. law%pairs(m)%body_b == b) .or. &
          (law%pairs(m)%body_a == b .and. law%pairs(m)%body_b == a)) mu = law%pairs(m)%friction
    end do
  end function pair_friction_of

end module voussoir_contact_law
