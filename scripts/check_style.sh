#!/usr/bin/env bash
# Style gate: clang-format on every tracked C++ file, and no ROS header in the ROS-free core.
# With --junit FILE, also writes the two checks as JUnit test cases.
set -uo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

junit=""
if [ "${1:-}" = "--junit" ]; then
  junit="$2"
fi

mapfile -t sources < <(git ls-files '*.cpp' '*.h' '*.hpp')
format_log=$(clang-format --dry-run --Werror "${sources[@]}" 2>&1)
format_ok=$?

ros_pattern='#include *[<"](ros/|sensor_msgs/|tf2_ros/|geometry_msgs/|visualization_msgs/|XmlRpc|pcl_conversions/|std_msgs/)'
core_leaks=$(grep -rnE "$ros_pattern" include/freeform_inspection src/core 2>/dev/null)
[ -z "$core_leaks" ]
core_ok=$?

[ $format_ok -eq 0 ] || printf 'clang-format differences:\n%s\n' "$format_log" >&2
[ $core_ok -eq 0 ] || printf 'ROS headers in the ROS-free core:\n%s\n' "$core_leaks" >&2

if [ -n "$junit" ]; then
  escape() { sed -e 's/&/\&amp;/g' -e 's/</\&lt;/g' -e 's/>/\&gt;/g'; }
  case_xml() {  # name ok log
    if [ "$2" -eq 0 ]; then
      printf '  <testcase classname="style" name="%s"/>\n' "$1"
    else
      printf '  <testcase classname="style" name="%s"><failure message="failed">%s</failure></testcase>\n' \
        "$1" "$(printf '%s' "$3" | head -c 20000 | escape)"
    fi
  }
  {
    echo '<?xml version="1.0" encoding="UTF-8"?>'
    echo '<testsuite name="style" tests="2">'
    case_xml clang_format "$format_ok" "$format_log"
    case_xml ros_free_core "$core_ok" "$core_leaks"
    echo '</testsuite>'
  } >"$junit"
fi

[ $format_ok -eq 0 ] && [ $core_ok -eq 0 ]
