!> The namelist group reader: every form the project's inputs use (lists, elements,
!> repeat counts, both quotes, logicals, comments, several lines, null values, &end) is
!> read to the same bits as gfortran's own NAMELIST read of the same file; bad values
!> are refused with the file, line, variable, what it expects and what it got; every
!> range of the tables can be read; the &arch rule of the sweep's lists holds as before.
program test_input
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t
  use voussoir_namelist_group, only: nml_group_t
  use voussoir_config, only: config_t, config_groups, arch_rule, arch_rule_text
  use voussoir_wall_config, only: wall_config_t, wall_group
  use voussoir_assert, only: assert_true, assert_summary
  implicit none

  !> What the test group fills.
  type :: sample_t
    real(dp) :: x = 1.0_dp, list(0:5) = -1.0_dp
    integer :: n = 7, counts(4) = 0
    logical :: on = .false., off = .true.
    character(len=16) :: mode = 'afd'
    character(len=64) :: file = ''
    character(len=32) :: names(3) = ''
  end type sample_t

  call test_same_bits_as_namelist()
  call test_refusals()
  call test_ranges_readable()
  call test_arch_rule()
  call assert_summary()

contains

  subroutine write_file(name, text)
    character(len=*), intent(in) :: name, text
    integer :: unit
    open (newunit=unit, file=name, status='replace', action='write')
    write (unit, '(a)') text
    close (unit)
  end subroutine write_file

  subroutine sample_group(s, g)
    type(sample_t), intent(inout), target :: s
    type(nml_group_t), intent(out) :: g
    g%name = 'test'
    call g%add('x', s%x, unit='m', range='0 < x <= 100 m')
    call g%add('list', s%list, first=0, unset=-1.0_dp, range='list >= 0')
    call g%add('n', s%n, range='1 <= n <= 10')
    call g%add('counts', s%counts)
    call g%add('on', s%on)
    call g%add('off', s%off)
    call g%add('mode', s%mode, choices=[character(len=16) :: 'afd', 'ramp'])
    call g%add('file', s%file)
    call g%add('names', s%names)
  end subroutine sample_group

  !> The same text read by the table and by a NAMELIST statement: equal to the bit.
  subroutine test_same_bits_as_namelist()
    character(len=*), parameter :: nl = new_line('a')
    type(sample_t), target :: s
    type(nml_group_t) :: g
    type(status_t) :: status
    real(dp) :: x, list(0:5)
    integer :: n, counts(4), unit, ios
    logical :: on, off, found
    character(len=16) :: mode
    character(len=64) :: file
    character(len=32) :: names(3)
    namelist /test/ x, list, n, counts, on, off, mode, file, names

    call write_file('test_input_same.nml', &
      '! a comment line, then another group first'//nl// &
      '&other a = 1 /'//nl// &
      '&test x = 0.1000000000000000055511151231257827, ! a comment after a value'//nl// &
      '  list = 3*0.046, , 2.5e-4 ; n = 3'//nl// &
      '  list(4) = 1.0d-3, counts = 1 2, 2*9 , on = T, off = .false.'//nl// &
      "  mode = 'RAMP', file = ""it's/a path.h5"", names = 'a''b', , ""c"""//nl// &
      '/'//nl)
    call sample_group(s, g)
    call g%read('test_input_same.nml', status)
    call assert_true(status%ok, 'a group of every form is read: '//trim(status%message))

    x = 1.0_dp; list = -1.0_dp; n = 7; counts = 0; on = .false.; off = .true.; mode = 'afd'; file = ''; names = ''
    open (newunit=unit, file='test_input_same.nml', status='old', action='read')
    read (unit, nml=test, iostat=ios)
    close (unit)
    call assert_true(ios == 0, 'gfortran reads the same group')
    call assert_true(s%x == x .and. all(s%list == list) .and. s%n == n .and. all(s%counts == counts), &
                     'numbers, lists, elements, nulls and repeats: the bits of the NAMELIST read')
    call assert_true(s%on .eqv. on .and. (s%off .eqv. off), 'logicals T and .false.')
    call assert_true(s%file == file .and. all(s%names == names), 'texts in both quotes, a doubled quote')
    call assert_true(s%mode == 'ramp' .and. mode == 'RAMP', 'a choice is kept in lower case')
    call assert_true(size(g%entries()) == 9 + 5 + 4 - 2, 'entries: a sparse list gives its set entries')

    ! &end closes a group as / does, and so does the end of the file (gfortran reads its
    ! values, then reports the end of the file).
    call write_file('test_input_end.nml', '&test n = 4'//nl//'&end'//nl)
    s = sample_t()
    call g%read('test_input_end.nml', status)
    call assert_true(status%ok .and. s%n == 4, '&end closes a group')
    call write_file('test_input_end.nml', '&test n = 5, x = 2')
    call g%read('test_input_end.nml', status)
    call assert_true(status%ok .and. s%n == 5 .and. s%x == 2.0_dp, 'the end of the file closes the last group')
    ! An absent group leaves the values.
    call write_file('test_input_end.nml', '&other n = 6 /')
    call g%read('test_input_end.nml', status, found=found)
    call assert_true(status%ok .and. .not. found .and. s%n == 5, 'an absent group: found = .false., values kept')
  end subroutine test_same_bits_as_namelist

  !> A refusal for each malformed value, naming what it expects and what it got.
  subroutine test_refusals()
    call refused('n = abc', 'test_input_bad.nml:1: &test n = abc is not a whole number')
    call refused('n = 99999999999', 'n = 99999999999 is not a whole number (an integer from')
    call refused('n = 1.5', 'n = 1.5 is not a whole number')
    call refused('x = ''wide''', "x = 'wide' is not a number")
    call refused('on = maybe', 'on = maybe is not a logical (.true. or .false.)')
    call refused('mode = ramp', "mode = ramp is not a text in quotes (write mode = 'ramp')")
    call refused('mode = ''ramp, n = 3', "&test mode: the text 'ramp, n = 3 / has no closing quote")
    call refused('nn = 3', "&test has no variable 'nn' (known: x, list, n,")
    call refused('n 3', "&test n is not followed by '='")
    call refused('n = 3 4', '&test n takes one value; it is given 2')
    call refused('n(2) = 3', 'n(2): n is one value, not a list')
    call refused('list(1) = 3 4', 'list(1) takes one value')
    call refused('list = 7*1', '&test list has 7 values; at most 6')
    call refused('list(9) = 1', '&test list has values up to entry 9; at most 5')
    call refused('list(-1) = 1', '&test list(-1): the entries of list are 0 to 5')
    call refused('list = 0*1', 'a repeat count r*value needs r >= 1')
  end subroutine test_refusals

  subroutine refused(body, expected)
    character(len=*), intent(in) :: body, expected
    type(sample_t), target :: s
    type(nml_group_t) :: g
    type(status_t) :: status
    call write_file('test_input_bad.nml', '&test '//body//' /')
    call sample_group(s, g)
    call g%read('test_input_bad.nml', status)
    call assert_true(.not. status%ok .and. index(status%message, expected) > 0, &
                     'refused: '//body//' -> '//trim(status%message))
  end subroutine refused

  !> Every range written in the tables reads as bounds, and a range is checked once.
  subroutine test_ranges_readable()
    type(config_t), target :: cfg
    type(wall_config_t), target :: w
    type(nml_group_t) :: groups(4), wall
    type(sample_t), target :: s
    type(status_t) :: status
    type(nml_group_t) :: g
    integer :: k, j
    logical :: all_valid
    call config_groups(cfg, groups)
    call wall_group(w, wall)
    all_valid = all(wall%vars%range%valid)
    do k = 1, size(groups)
      do j = 1, size(groups(k)%vars)
        all_valid = all_valid .and. groups(k)%vars(j)%range%valid
        if (.not. groups(k)%vars(j)%range%valid) print '(a)', 'unreadable: '//groups(k)%vars(j)%range%text
      end do
    end do
    call assert_true(all_valid, 'every range of &arch, &motion, &solver, &output, &wall reads')
    call sample_group(s, g)
    s%x = 0.0_dp
    call g%check('f.nml', status)
    call assert_true(trim(status%message) == 'f.nml: &test x = 0 is outside the allowed range 0 < x <= 100 m', &
                     'the one range message: '//trim(status%message))
    s%x = 1.0_dp
    s%list(3) = -2.0_dp
    status = status_t()
    call g%check('f.nml', status)
    call assert_true(index(status%message, '&test list(3) = -2 is outside the allowed range list >= 0') > 0, &
                     'a list entry is named with its index: '//trim(status%message))
    s%list(3) = -1.0_dp
    s%mode = 'square'
    status = status_t()
    call g%check('f.nml', status)
    call assert_true(trim(status%message) == "f.nml: &test mode = 'square' is not one of 'afd', 'ramp'", &
                     'a choice: '//trim(status%message))
  end subroutine test_ranges_readable

  !> The rule of &arch values and of the sweep's lists, as before the tables.
  subroutine test_arch_rule()
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_positive_inf
    call assert_true(arch_rule('embrace_deg', 180.0_dp) .and. .not. arch_rule('embrace_deg', 0.0_dp) .and. &
                     .not. arch_rule('embrace_deg', 180.5_dp), 'arch_rule: 0 < embrace_deg <= 180')
    call assert_true(arch_rule('n_voussoirs', 2.0_dp) .and. arch_rule('n_voussoirs', 1000.0_dp) .and. &
                     .not. arch_rule('n_voussoirs', 1001.0_dp), 'arch_rule: 2 <= n_voussoirs <= 1000')
    call assert_true(arch_rule('friction', 0.0_dp) .and. .not. arch_rule('friction', ieee_value(1.0_dp, ieee_positive_inf)) .and. &
                     .not. arch_rule('friction', -1.0e-9_dp), 'arch_rule: friction >= 0 (finite)')
    call assert_true(arch_rule('contact_inset_m', 0.0_dp) .and. .not. arch_rule('contact_inset_m', -1.0_dp), &
                     'arch_rule: contact_inset_m >= 0')
    call assert_true(arch_rule('size_imperfection', 0.0_dp) .and. .not. arch_rule('size_imperfection', 0.5_dp), &
                     'arch_rule: 0 <= size_imperfection < 0.5')
    call assert_true(arch_rule('thickness_m', 1000.0_dp) .and. .not. arch_rule('thickness_m', 0.0_dp), &
                     'arch_rule: 0 < thickness_m <= 1000 m')
    call assert_true(.not. arch_rule('polygon_file', 1.0_dp) .and. .not. arch_rule('nothing', 1.0_dp), &
                     'arch_rule: no rule for a variable without a range')
    call assert_true(arch_rule_text('density_kg_m3') == '0 < density_kg_m3 <= 1e5' .and. &
                     arch_rule_text('n_voussoirs') == '2 <= n_voussoirs <= 1000', 'arch_rule_text')
  end subroutine test_arch_rule

end program test_input
