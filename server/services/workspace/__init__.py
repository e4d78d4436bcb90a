"""A student's workspace as a resource of the server: its files, read and written within its folder
(``files.py``, ``paths.py``), its tree's version (``tree.py``), its zip (``archive.py``), new
packages (``package_create.py``), the lab's starting files (``templates.py``) and, on a class
server, where each world's workspace lives (``location.py``). Nothing here imports the web."""
