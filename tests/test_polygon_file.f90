!> The polygon-file parser fed line by line, without a file: line numbers in its
!> messages, comments and blanks, a block given clockwise, the checks at the end.
program test_polygon_file
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t
  use voussoir_assembly, only: assembly_t, role_voussoir, role_foundation
  use voussoir_polygon_file, only: polygon_reader_t, polygon_reader_init, polygon_reader_line, polygon_reader_end
  use voussoir_assert, only: assert_true, assert_summary
  implicit none

  call test_two_blocks()
  call test_vertex_before_block()
  call test_block_too_small_named_by_its_line()
  call test_overlap_found_at_the_end()
  call assert_summary()

contains

  !> Feed `lines` to a fresh reader named 'p.txt'; stop at the first failure.
  subroutine feed(lines, reader, status)
    character(len=*), intent(in) :: lines(:)
    type(polygon_reader_t), intent(out) :: reader
    type(status_t), intent(out) :: status
    integer :: k
    call polygon_reader_init(reader, 'p.txt')
    do k = 1, size(lines)
      call polygon_reader_line(reader, trim(lines(k)), status)
      if (.not. status%ok) return
    end do
  end subroutine feed

  subroutine test_two_blocks()
    type(polygon_reader_t) :: reader
    type(status_t) :: status
    type(assembly_t) :: a
    ! A driven base and a free unit square on it, given clockwise, with a comment and a blank.
    call feed([character(len=40) :: '# a block on a base', 'block driven', '-1 -1', '2 -1', '2 0', '-1 0', &
               '', 'block free   # the block', '0 0', '0 1', '1 1', '1 0'], reader, status)
    call assert_true(status%ok, 'polygon file: two blocks read')
    call assert_true(reader%line_no == 12 .and. reader%n_blocks == 2 .and. reader%block_line == 8, &
                     'polygon file: 12 lines, 2 blocks, the open one started on line 8')
    call polygon_reader_end(reader, a, status)
    call assert_true(status%ok .and. a%n_bodies == 2, 'polygon file: an assembly of 2 bodies')
    call assert_true(a%driven(1) .and. .not. a%driven(2), 'polygon file: the base driven, the block free')
    call assert_true(a%role(1) == role_foundation .and. a%role(2) == role_voussoir, 'polygon file: roles')
    ! Clockwise (0,0) (0,1) (1,1) (1,0) reversed: (1,0) (1,1) (0,1) (0,0), counter-clockwise.
    call assert_true(all(a%polygon(2)%xy == reshape([1, 0, 1, 1, 0, 1, 0, 0], [2, 4])), &
                     'polygon file: a clockwise block turned counter-clockwise')
  end subroutine test_two_blocks

  subroutine test_vertex_before_block()
    type(polygon_reader_t) :: reader
    type(status_t) :: status
    call feed([character(len=20) :: '# nothing yet', '0 0'], reader, status)
    call assert_true(.not. status%ok .and. index(status%message, "p.txt:2: expected a vertex 'x y'") == 1, &
                     'polygon file: a vertex before any block is refused on its line (2)')
  end subroutine test_vertex_before_block

  subroutine test_block_too_small_named_by_its_line()
    type(polygon_reader_t) :: reader
    type(status_t) :: status
    ! Block 1 (line 1) has two vertices; the next `block` (line 4) closes it.
    call feed([character(len=20) :: 'block free', '0 0', '1 0', 'block driven'], reader, status)
    call assert_true(.not. status%ok .and. &
                     trim(status%message) == 'p.txt:1: block 1 has fewer than 3 vertices', &
                     'polygon file: a block of 2 vertices, named by the line of its block')
  end subroutine test_block_too_small_named_by_its_line

  subroutine test_overlap_found_at_the_end()
    type(polygon_reader_t) :: reader
    type(status_t) :: status
    type(assembly_t) :: a
    ! Two unit squares, the second 0.5 m into the first: an overlap 0.5 m deep.
    call feed([character(len=20) :: 'block driven', '0 0', '1 0', '1 1', '0 1', &
               'block free', '0.5 0', '1.5 0', '1.5 1', '0.5 1'], reader, status)
    call assert_true(status%ok, 'polygon file: overlapping blocks read line by line')
    call polygon_reader_end(reader, a, status)
    call assert_true(.not. status%ok .and. index(status%message, 'p.txt: blocks 1 and 2 overlap by 0.5') == 1, &
                     'polygon file: the overlap of 0.5 m refused at the end: '//trim(status%message))
  end subroutine test_overlap_found_at_the_end

end program test_polygon_file
