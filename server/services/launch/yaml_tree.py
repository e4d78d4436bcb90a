"""YAML launch files as the same checked element tree as XML's: ROS 2's YAML frontend is the XML
one in another syntax (``launch:`` a list of actions, each a one-key mapping such as ``- node:
{pkg: ..., exec: ..., param: [{name: ..., value: ...}], remap: [...]}``; a group's actions in
``children:`` or as its list), so one evaluator reads both and a line number names the YAML line.
"""

from __future__ import annotations

from typing import NoReturn

import yaml

from server.services.launch.description import LaunchFileError
from server.services.launch.xml_tree import MAX_FILE_BYTES, MAX_NESTING, Element, check_tree

# Keys whose value is a list of elements, not an attribute: a node's parameters and remaps, an
# include's arguments, a group's actions.
ELEMENT_LISTS = ("param", "remap", "arg")
CHILDREN = "children"
MAX_YAML_NODES = 100_000  # an alias repeated by other aliases is walked once per use


class _Reader:
    def __init__(self, file: str) -> None:
        self.file = file
        self.seen = 0

    def fail(self, node: yaml.Node | None, problem: str) -> NoReturn:
        raise LaunchFileError(self.file, node.start_mark.line + 1 if node is not None else 0, problem)

    def count(self, node: yaml.Node, depth: int) -> None:
        self.seen += 1
        if self.seen > MAX_YAML_NODES:
            self.fail(node, f"more than {MAX_YAML_NODES} YAML values")
        if depth > MAX_NESTING:
            self.fail(node, f"entities are nested more than {MAX_NESTING} deep")

    def entities(self, node: yaml.Node, depth: int) -> list[Element]:
        if not isinstance(node, yaml.SequenceNode):
            self.fail(node, "expected a list of actions (each '- name:' with its attributes)")
        return [self.entity(item, depth + 1) for item in node.value]

    def entity(self, node: yaml.Node, depth: int) -> Element:
        self.count(node, depth)
        if not isinstance(node, yaml.MappingNode) or len(node.value) != 1:
            self.fail(node, "each action is a mapping with one key, its kind ('- node:', '- arg:', ...)")
        key, value = node.value[0]
        return self.element(self.text(key), value, node.start_mark.line + 1, depth)

    def element(self, tag: str, node: yaml.Node, line: int, depth: int) -> Element:
        self.count(node, depth)
        element = Element(tag, {}, line)
        if isinstance(node, yaml.SequenceNode):
            element.children = self.entities(node, depth)
            return element
        if isinstance(node, yaml.ScalarNode) and node.tag.endswith(":null"):
            return element  # '- group:' with nothing under it
        if not isinstance(node, yaml.MappingNode):
            self.fail(node, f"'{tag}' takes attributes (a mapping) or a list of actions")
        for key_node, value in node.value:
            key = self.text(key_node)
            if key == CHILDREN:
                element.children.extend(self.entities(value, depth))
            elif key in ELEMENT_LISTS and isinstance(value, yaml.SequenceNode):
                element.children.extend(
                    self.element(key, item, item.start_mark.line + 1, depth + 1) for item in value.value
                )
            elif key in element.attrs:
                self.fail(key_node, f"'{tag}' has '{key}' twice")
            else:
                element.attrs[key] = self.value(key, value)
        return element

    def text(self, node: yaml.Node) -> str:
        if not isinstance(node, yaml.ScalarNode):
            self.fail(node, "expected a name or a value, not a list or a mapping")
        return "" if node.tag.endswith(":null") else str(node.value)

    def value(self, key: str, node: yaml.Node) -> str:
        """An attribute's text; a list of values as launch XML writes one (``[1, 2]``)."""
        if isinstance(node, yaml.SequenceNode):
            items = [self._item(item) for item in node.value]
            return "[" + ", ".join(items) + "]"
        if isinstance(node, yaml.MappingNode):
            self.fail(node, f"'{key}' is a mapping; it takes a value or a list of values")
        return self.text(node)

    def _item(self, node: yaml.Node) -> str:
        text = self.text(node)
        quoted = isinstance(node, yaml.ScalarNode) and node.style in ("'", '"')
        return f"'{text}'" if quoted and "'" not in text else text


def load_yaml_tree(data: bytes, file: str) -> Element:
    """A YAML launch file as the element tree XML gives, checked against the same schema."""
    if len(data) > MAX_FILE_BYTES:
        raise LaunchFileError(file, 0, f"file is larger than {MAX_FILE_BYTES} bytes; refusing to parse it")
    try:
        root = yaml.compose(data.decode("utf-8"), Loader=yaml.SafeLoader)
    except UnicodeDecodeError as err:
        raise LaunchFileError(file, 0, f"not UTF-8 text: {err.reason}") from None
    except yaml.MarkedYAMLError as err:
        line = err.problem_mark.line + 1 if err.problem_mark is not None else 0
        raise LaunchFileError(file, line, f"not valid YAML: {err.problem or err}") from None
    except yaml.YAMLError as err:
        raise LaunchFileError(file, 0, f"not valid YAML: {err}") from None
    reader = _Reader(file)
    if (
        not isinstance(root, yaml.MappingNode)
        or len(root.value) != 1
        or reader.text(root.value[0][0]) != "launch"
    ):
        reader.fail(root, "a YAML launch file is one key, 'launch:', holding a list of actions")
    tree = reader.element("launch", root.value[0][1], root.start_mark.line + 1, 0)
    check_tree(tree, file)
    return tree
