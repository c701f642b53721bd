#!/usr/bin/env python3
"""Prints the shell commands of README.md's ROS sections, one per line, for check_readme_ros.sh.

ROS sections: the `## ` sections whose heading names ROS, rviz or a bag (with their `###`
subsections). Their commands: every command of a fenced block marked bash, sh, shell or nothing
(continuation lines joined, comments dropped), and every inline `code` span that begins with a ROS
tool and has arguments (`rostopic echo ...` in a sentence). A command written twice is printed once.
  scripts/readme_commands.py README.md
"""
import re
import sys

ROS_SECTION = re.compile(r"^## .*\b(ROS|rviz|bags?)\b", re.IGNORECASE)
SHELL_FENCE = re.compile(r"^```\s*(bash|sh|shell)?\s*$")
ROS_TOOLS = ("roslaunch", "rosrun", "rostopic", "rosservice", "rosbag", "rosparam", "rosnode",
             "roscore", "rviz", "xvfb-run")
INLINE_CODE = re.compile(r"`([^`]+)`")


def strip_comment(line):
    """The line without a shell comment: a # at the start or after a blank, outside quotes."""
    quote = None
    for i, c in enumerate(line):
        if quote:
            quote = None if c == quote else quote
        elif c in "'\"":
            quote = c
        elif c == "#" and (i == 0 or line[i - 1].isspace()):
            return line[:i]
    return line


def is_inline_command(span):
    """A ROS tool with arguments: `rostopic echo /x` is a command, `rviz` alone an argument."""
    words = span.split()
    return len(words) > 1 and words[0] in ROS_TOOLS


def fenced_commands(lines):
    """The commands of one fenced block's lines (a continued line's indentation becomes a blank)."""
    commands, pending = [], ""
    for line in lines:
        line = strip_comment(line).strip()
        if line.endswith("\\"):
            pending += line[:-1].rstrip() + " "
            continue
        command = pending + line
        pending = ""
        if command:
            commands.append(command)
    return commands


def ros_section_commands(text):
    commands = []
    in_ros_section, fence = False, None  # fence: the open block's lines, or None outside blocks
    keep_fence = False
    paragraph = []  # inline spans may run over a line break, never over a paragraph

    def end_paragraph():
        spans = INLINE_CODE.findall(" ".join(paragraph))
        commands.extend(c.strip() for c in spans if is_inline_command(c))
        paragraph.clear()

    for line in text.splitlines():
        if fence is not None:
            if line.startswith("```"):
                if keep_fence:
                    commands.extend(fenced_commands(fence))
                fence = None
            else:
                fence.append(line)
        elif line.startswith("```"):
            end_paragraph()
            fence = []
            keep_fence = in_ros_section and bool(SHELL_FENCE.match(line))
        elif line.startswith("#") or not line.strip():
            end_paragraph()
            if line.startswith("## "):
                in_ros_section = bool(ROS_SECTION.match(line))
        elif in_ros_section:
            paragraph.append(line)
    end_paragraph()
    return list(dict.fromkeys(commands))


def main():
    with open(sys.argv[1], encoding="utf-8") as f:
        for command in ros_section_commands(f.read()):
            print(command)


if __name__ == "__main__":
    main()
