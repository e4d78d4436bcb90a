"""The 3D page: viser's own client served on the app's port, with the scenes the views draw."""
