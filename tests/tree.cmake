# The rules the layout keeps (file and procedure lengths, files named after their
# modules, sweep modes only in their factory, the map in docs/architecture.md).
add_test(NAME tree_rules COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/tree/check_tree.py ${CMAKE_SOURCE_DIR})
