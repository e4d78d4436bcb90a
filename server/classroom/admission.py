"""Who may join a class, how fast: joins and wrong class codes per client address and for the
whole class, worlds per address, and names that print as one line.

An address that sent too many wrong codes is refused (429, with when to try again) before its
next code is even compared, so guessing runs at the limit's rate and no faster; the class's own
limit on wrong codes bounds guessing from many addresses. Another address with the right code
still joins while one address is throttled.
"""

from __future__ import annotations

import secrets
import unicodedata
from collections import Counter

from node_runtime.bus import Clock
from node_runtime.limits import KeyedRateLimit, RateLimit
from server.classroom.errors import (
    AddressLimitError,
    BadNameError,
    RateLimitedError,
    WrongCodeError,
)
from server.host.settings import JoinLimits

CODE_ALPHABET = "ABCDEFGHJKLMNPQRSTUVWXYZ23456789"  # no 0/O, 1/I: read aloud or off a projector
CODE_CHARS = 6
# Control, format, surrogate, private and unassigned characters, and line or paragraph
# separators: none belongs in a name that the console, the pages and the logs print on one line.
_NOT_PRINTABLE = frozenset({"Cc", "Cf", "Cs", "Co", "Cn", "Zl", "Zp"})


def new_code() -> str:
    """A class code: what a student types to join."""
    return "".join(secrets.choice(CODE_ALPHABET) for _ in range(CODE_CHARS))


def check_student_name(name: str) -> None:
    """BadNameError naming the first character a name may not hold."""
    for index, char in enumerate(name):
        if unicodedata.category(char) in _NOT_PRINTABLE:
            raise BadNameError(
                f"the name holds a control character (U+{ord(char):04X} at {index}): "
                "use letters, digits, spaces and punctuation",
            )


class Admission:
    """The class's door: every limit a join meets before its world starts."""

    def __init__(self, limits: JoinLimits, clock: Clock) -> None:
        self.limits = limits
        self.joins = KeyedRateLimit(clock, limits.per_address_hz, limits.per_address_burst)
        self.class_joins = RateLimit(clock, limits.class_hz, limits.class_burst)
        self.wrong = KeyedRateLimit(
            clock, limits.wrong_codes_per_address_hz, limits.wrong_codes_per_address_burst
        )
        self.class_wrong = RateLimit(clock, limits.wrong_codes_class_hz, limits.wrong_codes_class_burst)
        self.held: Counter[str] = Counter()  # worlds (and worlds starting) by the address that joined them

    def check(self, address: str) -> None:
        """Before the code is compared: RateLimitedError while this address or the class is throttled."""
        for limit, why in (
            (self.wrong[address], "too many wrong class codes from your address"),
            (self.class_wrong, "too many wrong class codes in this class"),
            (self.joins[address], "too many joins from your address"),
            (self.class_joins, "too many joins in this class just now"),
        ):
            if not limit.ready():
                limit.refused += 1
                after = limit.retry_after_s()
                raise RateLimitedError(f"{why}: try again in {max(1, round(after))} s", after)

    def wrong_code(self, address: str) -> WrongCodeError:
        """Charge a wrong code to its address and the class; the refusal to answer it with."""
        self.wrong[address].take()
        self.class_wrong.take()
        return WrongCodeError("wrong class code")

    def hold(self, address: str) -> None:
        """A world starts for ``address``: AddressLimitError over the cap of worlds per address, else
        charged."""
        cap = self.limits.max_worlds_per_address
        if cap is not None and self.held[address] >= cap:
            raise AddressLimitError(f"at most {cap} worlds per client address in this class")
        self.joins[address].take()
        self.class_joins.take()
        self.held[address] += 1

    def release(self, address: str | None) -> None:
        """A world of ``address`` is gone (removed, or its start failed)."""
        if address is not None and self.held[address] > 0:
            self.held[address] -= 1
            if not self.held[address]:
                del self.held[address]
