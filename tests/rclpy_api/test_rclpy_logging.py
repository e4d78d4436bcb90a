"""rclpy.logging: per-logger levels, severities, and rclpy's once / skip_first options."""

from __future__ import annotations

import pytest
import rclpy.logging
from rclpy.logging import LoggingSeverity


def test_a_loggers_level_hides_lines_below_it_and_unset_follows_the_process(
    capsys: pytest.CaptureFixture[str],
) -> None:
    logger = rclpy.logging.get_logger("level_test")
    try:
        rclpy.logging.set_logger_level("level_test", LoggingSeverity.ERROR)
        assert rclpy.logging.get_logger_effective_level("level_test") == LoggingSeverity.ERROR
        assert not logger.is_enabled_for(LoggingSeverity.WARN)
        logger.warning("a hidden warning")
        logger.error("a shown error")
        logger.set_level(LoggingSeverity.DEBUG)
        logger.debug("a shown debug line")
    finally:
        logger.set_level(LoggingSeverity.UNSET)
    logger.debug("a hidden debug line")  # the process's INFO again
    err = capsys.readouterr().err
    assert "[ERROR]" in err and "[level_test]: a shown error" in err and "a shown debug line" in err
    assert "hidden" not in err


def test_once_and_skip_first_count_per_call_site(capsys: pytest.CaptureFixture[str]) -> None:
    logger = rclpy.logging.get_logger("site_test")
    for i in range(3):
        logger.info(f"once {i}", once=True)
        logger.info(f"skip {i}", skip_first=True)
    err = capsys.readouterr().err
    assert "once 0" in err and "once 1" not in err and "once 2" not in err
    assert "skip 0" not in err and "skip 1" in err and "skip 2" in err
