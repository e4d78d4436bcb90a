"""example_interfaces for the differential suite's oracle: test_msgs' identical Fibonacci (README.md)."""
