"""Browser ``KeyboardEvent`` → SDL 1.2 key codes and modifier bits, as keyboard_msgs/Key carries them."""

from __future__ import annotations

from collections.abc import Mapping

from node_runtime.msgs import Key

# KeyboardEvent.key values that are not a single printable character.
_NAMED: dict[str, int] = {
    "Backspace": Key.KEY_BACKSPACE,
    "Tab": Key.KEY_TAB,
    "Clear": Key.KEY_CLEAR,
    "Enter": Key.KEY_RETURN,
    "Pause": Key.KEY_PAUSE,
    "Escape": Key.KEY_ESCAPE,
    "Delete": Key.KEY_DELETE,
    " ": Key.KEY_SPACE,
    "Spacebar": Key.KEY_SPACE,
    "ArrowUp": Key.KEY_UP,
    "ArrowDown": Key.KEY_DOWN,
    "ArrowRight": Key.KEY_RIGHT,
    "ArrowLeft": Key.KEY_LEFT,
    "Insert": Key.KEY_INSERT,
    "Home": Key.KEY_HOME,
    "End": Key.KEY_END,
    "PageUp": Key.KEY_PAGEUP,
    "PageDown": Key.KEY_PAGEDOWN,
    "NumLock": Key.KEY_NUMLOCK,
    "CapsLock": Key.KEY_CAPSLOCK,
    "ScrollLock": Key.KEY_SCROLLOCK,
    "AltGraph": Key.KEY_MODE,
    "Compose": Key.KEY_COMPOSE,
    "Help": Key.KEY_HELP,
    "PrintScreen": Key.KEY_PRINT,
    "ContextMenu": Key.KEY_MENU,
    "Power": Key.KEY_POWER,
    "Undo": Key.KEY_UNDO,
}
_NAMED.update({f"F{i}": Key.KEY_F1 + i - 1 for i in range(1, 16)})
# Left/right pairs: KeyboardEvent.location 2 is the right-hand key.
_SIDED = {
    "Shift": (Key.KEY_LSHIFT, Key.KEY_RSHIFT),
    "Control": (Key.KEY_LCTRL, Key.KEY_RCTRL),
    "Alt": (Key.KEY_LALT, Key.KEY_RALT),
    "Meta": (Key.KEY_LMETA, Key.KEY_RMETA),
    "OS": (Key.KEY_LSUPER, Key.KEY_RSUPER),
}
# KeyboardEvent.code values of the numeric keypad (location 3).
_KEYPAD = {f"Numpad{d}": Key.KEY_KP0 + d for d in range(10)}
_KEYPAD |= {
    "NumpadDecimal": Key.KEY_KP_PERIOD,
    "NumpadDivide": Key.KEY_KP_DIVIDE,
    "NumpadMultiply": Key.KEY_KP_MULTIPLY,
    "NumpadSubtract": Key.KEY_KP_MINUS,
    "NumpadAdd": Key.KEY_KP_PLUS,
    "NumpadEnter": Key.KEY_KP_ENTER,
    "NumpadEqual": Key.KEY_KP_EQUALS,
}
_PRINTABLE = {v for k, v in Key.__dict__.items() if k.startswith("KEY_") and 32 <= v <= 127}
_MODIFIER_FLAGS: dict[str, int] = {
    "lshift": Key.MODIFIER_LSHIFT,
    "rshift": Key.MODIFIER_RSHIFT,
    "lctrl": Key.MODIFIER_LCTRL,
    "rctrl": Key.MODIFIER_RCTRL,
    "lalt": Key.MODIFIER_LALT,
    "ralt": Key.MODIFIER_RALT,
    "lmeta": Key.MODIFIER_LMETA,
    "rmeta": Key.MODIFIER_RMETA,
    "num": Key.MODIFIER_NUM,
    "caps": Key.MODIFIER_CAPS,
    "mode": Key.MODIFIER_MODE,
    # Sides unknown: count as the left-hand key, as most keyboards send.
    "shift": Key.MODIFIER_LSHIFT,
    "ctrl": Key.MODIFIER_LCTRL,
    "alt": Key.MODIFIER_LALT,
    "meta": Key.MODIFIER_LMETA,
}
MODIFIER_FLAG_NAMES = tuple(_MODIFIER_FLAGS)


class UnknownKeyError(ValueError):
    def __init__(self, key: str) -> None:
        self.key = key
        super().__init__(f"unknown key {key!r}: no SDL key code for it")


def sdl_code(key: str, code: str | None = None, location: int | None = None) -> int:
    """The SDL key code for ``KeyboardEvent.key`` (plus ``.code`` and ``.location`` where they tell more)."""
    if code in _KEYPAD and (location in (None, 3)):
        return int(_KEYPAD[code])
    if key in _SIDED:
        left, right = _SIDED[key]
        return int(right if location == 2 else left)
    if key in _NAMED:
        return _NAMED[key]
    if len(key) == 1:
        # SDL 1.2 reports letters in lower case whatever Shift does; Shift shows in the modifiers.
        ordinal = ord(key.lower())
        if ordinal in _PRINTABLE:
            return ordinal
    raise UnknownKeyError(key)


def modifier_bits(flags: Mapping[str, object]) -> int:
    """OR of the MODIFIER_* bits whose flag is true; unknown flag names are an error."""
    bits = 0
    for name, on in flags.items():
        if name not in _MODIFIER_FLAGS:
            raise ValueError(f"unknown modifier flag {name!r} (known: {', '.join(MODIFIER_FLAG_NAMES)})")
        if not isinstance(on, bool):
            raise ValueError(f"modifier flag {name!r} must be true or false, got {on!r}")
        if on:
            bits |= _MODIFIER_FLAGS[name]
    return bits
