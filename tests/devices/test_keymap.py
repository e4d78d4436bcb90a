"""Browser KeyboardEvent → SDL 1.2 key codes and modifier bits (ref §2.1-2.2)."""

from __future__ import annotations

import pytest

from node_runtime.msgs import Key
from server.peripherals.devices.keymap import MODIFIER_FLAG_NAMES, UnknownKeyError, modifier_bits, sdl_code


@pytest.mark.parametrize(("key", "code"), [("a", 97), ("b", 98), ("z", 122), ("m", 109)])
def test_sdl_code_lower_case_letter_is_ascii(key: str, code: int) -> None:
    assert sdl_code(key) == code


@pytest.mark.parametrize(("key", "code"), [("A", 97), ("B", 98), ("Z", 122)])
def test_sdl_code_upper_case_letter_is_lower_case_code(key: str, code: int) -> None:
    # SDL 1.2: Shift shows only in the modifiers.
    assert sdl_code(key) == code


@pytest.mark.parametrize(
    ("key", "code"),
    [
        (" ", 32),
        ("Spacebar", 32),
        ("Enter", 13),
        ("Escape", 27),
        ("Backspace", 8),
        ("Tab", 9),
        ("Delete", 127),
        ("ArrowUp", 273),
        ("ArrowDown", 274),
        ("ArrowRight", 275),
        ("ArrowLeft", 276),
        ("Insert", 277),
        ("Home", 278),
        ("End", 279),
        ("PageUp", 280),
        ("PageDown", 281),
        ("F1", 282),
        ("F2", 283),
        ("F12", 293),
        ("F15", 296),
        ("NumLock", 300),
        ("CapsLock", 301),
        ("ScrollLock", 302),
        ("Pause", 19),
    ],
)
def test_sdl_code_named_key_maps_to_sdl(key: str, code: int) -> None:
    assert sdl_code(key) == code


@pytest.mark.parametrize(("key", "code"), [("0", 48), ("9", 57), ("!", 33), ("/", 47), ("[", 91), ("`", 96)])
def test_sdl_code_printable_ascii_maps_to_itself(key: str, code: int) -> None:
    assert sdl_code(key) == code


@pytest.mark.parametrize(
    ("key", "location", "code"),
    [
        ("Shift", 2, 303),
        ("Shift", 1, 304),
        ("Shift", 0, 304),
        ("Shift", None, 304),
        ("Control", 2, 305),
        ("Control", 1, 306),
        ("Alt", 2, 307),
        ("Alt", 1, 308),
        ("Meta", 2, 309),
        ("Meta", 1, 310),
    ],
)
def test_sdl_code_sided_modifier_key_location_2_is_right(key: str, location: int | None, code: int) -> None:
    assert sdl_code(key, location=location) == code


@pytest.mark.parametrize(
    ("key", "code", "sdl"),
    [
        ("0", "Numpad0", 256),
        ("5", "Numpad5", 261),
        ("9", "Numpad9", 265),
        (".", "NumpadDecimal", 266),
        ("/", "NumpadDivide", 267),
        ("*", "NumpadMultiply", 268),
        ("-", "NumpadSubtract", 269),
        ("+", "NumpadAdd", 270),
        ("Enter", "NumpadEnter", 271),
        ("=", "NumpadEqual", 272),
    ],
)
def test_sdl_code_numpad_key_maps_to_keypad_code(key: str, code: str, sdl: int) -> None:
    assert sdl_code(key, code=code, location=3) == sdl


def test_sdl_code_digit_row_with_code_is_not_keypad() -> None:
    assert sdl_code("0", code="Digit0", location=0) == 48
    assert sdl_code("Enter", code="Enter", location=0) == 13


@pytest.mark.parametrize("key", ["%", "Dead", "\u20ac", "", "Unidentified", "\u00e9", "ab"])
def test_sdl_code_unknown_key_raises_naming_key(key: str) -> None:
    with pytest.raises(UnknownKeyError) as err:
        sdl_code(key)
    assert err.value.key == key
    assert repr(key) in str(err.value)
    assert isinstance(err.value, ValueError)


def test_sdl_code_every_result_is_a_key_constant() -> None:
    constants = {v for n, v in vars(Key).items() if n.startswith("KEY_")}
    keys = ["a", "Z", " ", "Enter", "ArrowLeft", "F7", "Shift", "Alt", "AltGraph", "ContextMenu", "Undo"]
    assert all(sdl_code(k) in constants for k in keys)


def test_modifier_bits_no_flags_is_zero() -> None:
    assert modifier_bits({}) == 0
    assert modifier_bits(dict.fromkeys(MODIFIER_FLAG_NAMES, False)) == 0


@pytest.mark.parametrize(
    ("flags", "bits"),
    [
        ({"lshift": True}, 1),
        ({"rshift": True}, 2),
        ({"lctrl": True}, 64),
        ({"rctrl": True}, 128),
        ({"lalt": True}, 256),
        ({"ralt": True}, 512),
        ({"lmeta": True}, 1024),
        ({"rmeta": True}, 2048),
        ({"num": True}, 4096),
        ({"caps": True}, 8192),
        ({"mode": True}, 16384),
        ({"shift": True}, 1),
        ({"ctrl": True}, 64),
        ({"alt": True}, 256),
        ({"meta": True}, 1024),
        ({"shift": True, "ctrl": True, "num": True}, 1 | 64 | 4096),
        ({"shift": True, "alt": False}, 1),
    ],
)
def test_modifier_bits_flags_or_to_modifier_constants(flags: dict[str, bool], bits: int) -> None:
    assert modifier_bits(flags) == bits


def test_modifier_bits_unknown_flag_raises_naming_it() -> None:
    with pytest.raises(ValueError, match="'hyper'"):
        modifier_bits({"hyper": True})


def test_modifier_bits_non_bool_flag_raises() -> None:
    with pytest.raises(ValueError, match="'shift'"):
        modifier_bits({"shift": 1})
