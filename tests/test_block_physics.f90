!> Single blocks against closed-form answers (shared/DESIGN.md):
!> a block on an incline sticks when tan(slope) <= mu and otherwise slides with
!> a = g (sin - mu cos), also when mu is given to its joint alone (joint_friction) and
!> every other contact is rougher; a block of half-width b and half-height h starts to rock at a
!> horizontal acceleration g b / h; in free rocking its amplitudes follow Housner's exact
!> recursion cos(alpha - th_k+1) - cos(alpha) = r^2 (cos(alpha - th_k) - cos(alpha)) with
!> r = 1 - 1.5 sin^2(alpha), alpha = atan(b / h). A block carrying a column of fill
!> (a bridge's fill as mass, docs/bridges.md): its mass, centre of mass and inertia those
!> of the composite body (rectangles, by hand), and it starts to rock at g b / y_c, y_c the
!> height of the composite's centre of mass.
program test_block_physics
  use voussoir_kinds, only: dp, pi, g_m_s2
  use voussoir_status, only: status_t
  use voussoir_assembly, only: assembly_t, polygon_t, role_voussoir, role_foundation
  use voussoir_geometry, only: rotate2
  use voussoir_model, only: model_t, model_step, solver_settings_t
  use voussoir_motion, only: motion_ramp
  use voussoir_setup, only: init_model
  use voussoir_contact_law, only: contact_law_t, contact_law_init
  use voussoir_assert, only: assert_true, assert_close, assert_summary
  implicit none

  call incline(slope_deg=20.0_dp, mu=0.5_dp)
  call incline(slope_deg=35.0_dp, mu=0.5_dp)
  call incline(slope_deg=30.0_dp, mu=0.2_dp)
  ! The same slope with a rough default (0.9, it would stick) and 0.2 on joint 0 only.
  call incline(slope_deg=30.0_dp, mu=0.2_dp, default_mu=0.9_dp)
  call incline(slope_deg=30.0_dp, mu=0.7_dp, default_mu=0.1_dp)
  call uplift(half_width_m=0.1_dp, half_height_m=0.5_dp)
  call uplift(half_width_m=0.15_dp, half_height_m=0.3_dp)
  call fill_column_mass()
  call uplift_with_fill(column_m=0.4_dp, fill_density_kg_m3=2000.0_dp)
  call uplift_with_fill(column_m=1.0_dp, fill_density_kg_m3=1800.0_dp)
  call free_rocking()
  call assert_summary()

contains

  !> A rectangle (half sizes b, h) standing on its base centred at `base`, rotated by
  !> `angle` about that point; vertices counter-clockwise.
  function block(b, h, base, angle) result(p)
    real(dp), intent(in) :: b, h, base(2), angle
    type(polygon_t) :: p
    real(dp) :: local(2, 4)
    integer :: k
    local = reshape([-b, 0.0_dp, b, 0.0_dp, b, 2*h, -b, 2*h], [2, 4])
    allocate (p%xy(2, 4))
    do k = 1, 4
      p%xy(:, k) = base + rotate2(local(:, k), angle)
    end do
  end function block

  !> An assembly of one free block on one driven ground polygon, numbered as a one-voussoir
  !> arch: joint 0 between the ground and the block (joint 1 the same pair).
  function two_bodies(free_block, ground) result(a)
    type(polygon_t), intent(in) :: free_block, ground
    type(assembly_t) :: a
    a%n_bodies = 2
    a%polygon = [free_block, ground]
    a%driven = [.false., .true.]
    a%role = [role_voussoir, role_foundation]
    a%n_voussoirs = 1
    allocate (a%joint_bodies(2, 0:1))
    a%joint_bodies(:, 0) = [2, 1]
    a%joint_bodies(:, 1) = [1, 2]
  end function two_bodies

  function settings(dt_s) result(s)
    real(dp), intent(in) :: dt_s
    type(solver_settings_t) :: s
    s%dt_s = dt_s
    s%tol = 1.0e-8_dp
    s%max_iter = 5000
    s%alert_m = 1.0e-3_dp
  end function settings

  !> Friction `mu` everywhere, or `default_mu` everywhere but `mu` on joint 0.
  function law(mu, default_mu) result(l)
    real(dp), intent(in) :: mu
    real(dp), intent(in), optional :: default_mu
    type(contact_law_t) :: l
    real(dp) :: joint_friction(0:1)
    type(assembly_t) :: numbering
    type(status_t) :: status
    type(polygon_t) :: none
    allocate (none%xy(2, 0))
    numbering = two_bodies(none, none)
    joint_friction = -1.0_dp
    if (.not. present(default_mu)) then
      call contact_law_init(mu, 0.0_dp, joint_friction, numbering, l, status)
    else
      joint_friction(0) = mu
      call contact_law_init(default_mu, 0.0_dp, joint_friction, numbering, l, status)
    end if
    call assert_true(status%ok, 'contact law: '//trim(status%message))
  end function law

  subroutine incline(slope_deg, mu, default_mu)
    real(dp), intent(in) :: slope_deg, mu
    real(dp), intent(in), optional :: default_mu   !! other contacts; mu then on joint 0 only
    type(model_t) :: model
    type(status_t) :: status
    type(polygon_t) :: ground
    real(dp) :: alpha, length, t_end, along(2), start(2), s_m, a_expected, a_sim
    character(len=64) :: label
    integer :: k

    alpha = slope_deg*pi/180.0_dp
    length = 20.0_dp
    ground%xy = reshape([0.0_dp, -1.0_dp, length*cos(alpha), -1.0_dp, &
                         length*cos(alpha), length*sin(alpha), 0.0_dp, 0.0_dp], [2, 4])
    along = [cos(alpha), sin(alpha)]
    call init_model(two_bodies(block(0.2_dp, 0.05_dp, 0.5_dp*length*along, alpha), ground), &
                    2000.0_dp, 1.0_dp, settings(1.0e-3_dp), law(mu, default_mu), model, status)
    call assert_true(status%ok, 'incline model builds')
    start = model%bodies%q(1:2, 1)
    t_end = 1.0_dp
    do k = 1, nint(t_end/model%solver%dt_s)
      call model_step(model, status)
      if (.not. status%ok) exit
    end do
    call assert_true(status%ok, 'incline run: '//trim(status%message))
    ! Distance travelled down the slope.
    s_m = -dot_product(model%bodies%q(1:2, 1) - start, along)
    write (label, '(a,f0.1,a,f0.2)') 'incline ', slope_deg, ' deg, mu ', mu
    if (present(default_mu)) write (label, '(a,a,f0.2)') trim(label), ' on joint 0, elsewhere ', default_mu
    if (tan(alpha) <= mu) then
      call assert_true(abs(s_m) < 1.0e-6_dp, trim(label)//': block sticks')
    else
      a_expected = g_m_s2*(sin(alpha) - mu*cos(alpha))
      a_sim = 2.0_dp*s_m/t_end**2
      call assert_close(a_sim, a_expected, trim(label)//': sliding acceleration [m/s2]', rtol=0.01_dp)
      ! It slides without leaving the slope or turning.
      call assert_true(abs(model%bodies%q(3, 1)) < 1.0e-6_dp, trim(label)//': no rotation while sliding')
    end if
  end subroutine incline

  !> The table acceleration / g at which block 1 starts to turn (|rotation| > 1e-5 rad)
  !> under a table acceleration ramped at `rate_m_s3`, run up to twice the `expected`
  !> value; -1 when it never turns.
  function tipping_load_factor(model, rate_m_s3, expected, status) result(lambda)
    type(model_t), intent(inout) :: model
    real(dp), intent(in) :: rate_m_s3, expected
    type(status_t), intent(inout) :: status
    real(dp) :: lambda
    integer :: k
    model%motion = motion_ramp(rate_m_s3)
    lambda = -1.0_dp
    do k = 1, nint(2.0_dp*expected*g_m_s2/rate_m_s3/model%solver%dt_s)
      call model_step(model, status)
      if (.not. status%ok) exit
      if (abs(model%bodies%q(3, 1)) > 1.0e-5_dp) then
        lambda = rate_m_s3*model%t_s/g_m_s2
        exit
      end if
    end do
  end function tipping_load_factor

  !> Slow ramp of horizontal load: the block tips when the load reaches g b / h.
  subroutine uplift(half_width_m, half_height_m)
    real(dp), intent(in) :: half_width_m, half_height_m
    type(model_t) :: model
    type(status_t) :: status
    type(polygon_t) :: ground
    real(dp), parameter :: rate_m_s3 = 0.05_dp
    real(dp) :: lambda_sim
    character(len=64) :: label

    ground%xy = reshape([-2.0_dp, -0.5_dp, 2.0_dp, -0.5_dp, 2.0_dp, 0.0_dp, -2.0_dp, 0.0_dp], [2, 4])
    call init_model(two_bodies(block(half_width_m, half_height_m, [0.0_dp, 0.0_dp], 0.0_dp), ground), &
                    2000.0_dp, 1.0_dp, settings(1.0e-3_dp), law(0.9_dp), model, status)
    lambda_sim = tipping_load_factor(model, rate_m_s3, half_width_m/half_height_m, status)
    write (label, '(a,f0.2,a,f0.2)') 'uplift of a block b = ', half_width_m, ', h = ', half_height_m
    call assert_true(status%ok, trim(label)//': run '//trim(status%message))
    call assert_close(lambda_sim, half_width_m/half_height_m, trim(label)//': uplift acceleration / g', &
                      rtol=0.02_dp)
  end subroutine uplift

  !> One block (half sizes b, h) on the ground under a fill of `fill_density_kg_m3` up to
  !> `column_m` above its top: a column as wide as the block stands on it.
  function block_under_fill(b, h, column_m, fill_density_kg_m3, width_m) result(a)
    real(dp), intent(in) :: b, h, column_m, fill_density_kg_m3, width_m
    type(assembly_t) :: a
    type(polygon_t) :: ground
    ground%xy = reshape([-2.0_dp, -0.5_dp, 2.0_dp, -0.5_dp, 2.0_dp, 0.0_dp, -2.0_dp, 0.0_dp], [2, 4])
    a = two_bodies(block(b, h, [0.0_dp, 0.0_dp], 0.0_dp), ground)
    a%has_fill = .true.
    a%fill_level_m = 2*h + column_m
    a%fill_weight_n_m2 = fill_density_kg_m3*g_m_s2*width_m
  end function block_under_fill

  !> A block 2b x 2h (density rho_b) carrying a column 2b x H of fill (rho_f), width w: the
  !> composite body of two rectangles, m = m_b + m_f with m_b = rho_b w 4 b h and
  !> m_f = rho_f w 2 b H, its centre of mass at x = 0, y_c = (m_b h + m_f (2h + H/2))/m,
  !> its inertia about it m_b (4b^2 + 4h^2)/12 + m_b (h - y_c)^2 + m_f (4b^2 + H^2)/12
  !> + m_f (2h + H/2 - y_c)^2; the vertices stay where they were.
  subroutine fill_column_mass()
    real(dp), parameter :: b = 0.15_dp, h = 0.3_dp, column = 0.4_dp, rho_b = 2200.0_dp, rho_f = 1900.0_dp
    real(dp), parameter :: w = 1.5_dp
    type(model_t) :: model
    type(status_t) :: status
    real(dp) :: m_b, m_f, y_c, inertia, corner(2)
    m_b = rho_b*w*4*b*h
    m_f = rho_f*w*2*b*column
    y_c = (m_b*h + m_f*(2*h + column/2))/(m_b + m_f)
    inertia = m_b*(4*b**2 + 4*h**2)/12 + m_b*(h - y_c)**2 + m_f*(4*b**2 + column**2)/12 + m_f*(2*h + column/2 - y_c)**2
    call init_model(block_under_fill(b, h, column, rho_f, w), rho_b, w, settings(1.0e-3_dp), law(0.9_dp), model, status)
    call assert_true(status%ok, 'fill column: init '//trim(status%message))
    call assert_close(model%bodies%mass_kg(1), m_b + m_f, 'fill column: composite mass', rtol=1.0e-12_dp)
    call assert_close(1.0_dp/model%bodies%inv_mass(1), m_b + m_f, 'fill column: inverse mass', rtol=1.0e-12_dp)
    call assert_close(model%bodies%q(1, 1), 0.0_dp, 'fill column: centre of mass x', atol=1.0e-12_dp)
    call assert_close(model%bodies%q(2, 1), y_c, 'fill column: centre of mass y', rtol=1.0e-12_dp)
    call assert_close(model%bodies%inertia_kg_m2(1), inertia, 'fill column: centroidal inertia', rtol=1.0e-12_dp)
    call assert_close(1.0_dp/model%bodies%inv_inertia(1), inertia, 'fill column: inverse inertia', rtol=1.0e-12_dp)
    ! The block's bottom right corner (b, 0) stays where it is.
    corner = model%bodies%vertex(:, 2, 1)
    call assert_close(corner(1), b, 'fill column: corner x', atol=1.0e-12_dp)
    call assert_close(corner(2), 0.0_dp, 'fill column: corner y', atol=1.0e-12_dp)
  end subroutine fill_column_mass

  !> Slow ramp of horizontal load on a block 0.3 m x 0.6 m (2000 kg/m3) carrying a column of
  !> fill as wide: it tips about its corner when the table's acceleration reaches g b / y_c
  !> (the moment of the whole mass's inertial load, m a y_c, reaches that of its weight,
  !> m g b), y_c the composite's centre of mass (as in fill_column_mass). With the fill as a
  !> constant force on the top it would tip at g b (m_b + m_f)/(m_b h) instead.
  subroutine uplift_with_fill(column_m, fill_density_kg_m3)
    real(dp), intent(in) :: column_m, fill_density_kg_m3
    real(dp), parameter :: b = 0.15_dp, h = 0.3_dp, rho_b = 2000.0_dp, rate_m_s3 = 0.05_dp
    type(model_t) :: model
    type(status_t) :: status
    real(dp) :: lambda_sim, m_b, m_f, y_c
    character(len=80) :: label
    m_b = rho_b*4*b*h
    m_f = fill_density_kg_m3*2*b*column_m
    y_c = (m_b*h + m_f*(2*h + column_m/2))/(m_b + m_f)
    call init_model(block_under_fill(b, h, column_m, fill_density_kg_m3, 1.0_dp), rho_b, 1.0_dp, &
                    settings(1.0e-3_dp), law(0.9_dp), model, status)
    lambda_sim = tipping_load_factor(model, rate_m_s3, b/y_c, status)
    write (label, '(a,f0.2,a)') 'uplift of a block under ', column_m, ' m of fill'
    call assert_true(status%ok, trim(label)//': run '//trim(status%message))
    call assert_close(lambda_sim, b/y_c, trim(label)//': uplift acceleration / g', rtol=0.02_dp)
  end subroutine uplift_with_fill

  !> Free rocking of a 0.2 m x 1.0 m block released at half its slenderness angle.
  subroutine free_rocking()
    real(dp), parameter :: b = 0.1_dp, h = 0.5_dp
    type(model_t) :: model
    type(status_t) :: status
    type(polygon_t) :: ground
    real(dp) :: alpha, r, theta0, expected(0:5), peak, previous_sign
    real(dp) :: found(5)
    integer :: k, n_found
    character(len=48) :: label

    alpha = atan(b/h)
    theta0 = 0.5_dp*alpha
    r = 1.0_dp - 1.5_dp*sin(alpha)**2
    expected(0) = theta0
    do k = 1, 5
      expected(k) = alpha - acos(cos(alpha) + r**2*(cos(alpha - expected(k - 1)) - cos(alpha)))
    end do

    ground%xy = reshape([-2.0_dp, -0.5_dp, 2.0_dp, -0.5_dp, 2.0_dp, 0.0_dp, -2.0_dp, 0.0_dp], [2, 4])
    ! Tilted by theta0 about its left corner (-b, 0).
    call init_model(two_bodies(block(b, h, [-b + b*cos(theta0), b*sin(theta0)], theta0), ground), &
                    2000.0_dp, 1.0_dp, settings(1.0e-4_dp), law(0.8_dp), model, status)
    n_found = 0
    peak = 0.0_dp
    previous_sign = 1.0_dp
    do k = 1, 60000
      call model_step(model, status)
      if (.not. status%ok) exit
      ! The reference configuration is the tilted one: add the initial tilt.
      associate (th => theta0 + model%bodies%q(3, 1))
        if (sign(1.0_dp, th) /= previous_sign .and. abs(th) > 1.0e-9_dp) then
          ! An impact: the peak of the half cycle just ended is complete.
          if (k > 1 .and. peak < 0.99_dp*theta0) then
            n_found = n_found + 1
            found(n_found) = peak
            if (n_found == 5) exit
          end if
          previous_sign = sign(1.0_dp, th)
          peak = 0.0_dp
        end if
        peak = max(peak, abs(th))
      end associate
    end do
    call assert_true(status%ok .and. n_found == 5, 'free rocking: five half cycles found')
    do k = 1, n_found
      write (label, '(a,i0,a)') 'free rocking: peak ', k, ' [rad] (Housner)'
      call assert_close(found(k), expected(k), trim(label), rtol=0.02_dp)
    end do
  end subroutine free_rocking

end program test_block_physics
