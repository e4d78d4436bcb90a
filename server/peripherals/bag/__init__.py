"""Record and replay like ``ros2 bag``: MCAP bags (profile ros2, CDR, ros2msg schemas) that
``ros2 bag info``, Foxglove and Lichtblick open."""
