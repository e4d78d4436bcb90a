"""What every request passes through before a route: the guard, the path as sent, strict JSON,
the cap on a student's sockets, refused sockets, and a worker's worlds passed on."""
