"""Scenes: rooms as triangle meshes with materials, people, and the radar's pose."""
