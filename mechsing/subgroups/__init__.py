"""Lie subgroups of D: the catalog of types, subgroup instances, identification.

* :func:`load_catalog` -- the types, read from ``catalog/*.toml``;
* :class:`Subgroup` -- a type with its geometric parameters (basis, exp
  chart, conjugation, membership, canonical comparison);
* :func:`identify` -- type and parameters of the Lie closure of any screws;
* :func:`generate`, :func:`intersect`, :func:`product` (generated subgroups, intersections and products).
"""

from mechsing.subgroups.algebra import (
    Identification,
    Intersection,
    Product,
    generate,
    identify,
    intersect,
    lie_closure,
    product,
)
from mechsing.subgroups.instance import Subgroup
from mechsing.subgroups.types import CatalogError, SubgroupType, in_plane, load_catalog

__all__ = [
    "CatalogError",
    "Identification",
    "Intersection",
    "Product",
    "Subgroup",
    "SubgroupType",
    "generate",
    "identify",
    "in_plane",
    "intersect",
    "lie_closure",
    "load_catalog",
    "product",
]
