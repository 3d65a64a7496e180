"""Exudyn items as the short dictionaries ``mbs.AddNode``/``AddObject``/... take: :data:`ii`.

``ii.ObjectJointRevolute2D(markerNumbers=[m0, m1])`` here takes the keywords of
``exudyn.itemInterface.ObjectJointRevolute2D`` and returns ``{"objectType": "JointRevolute2D",
"markerNumbers": [m0, m1]}``: only the fields given (a ``visualization`` dictionary becomes its
``V``-prefixed fields, as the item interface writes them), Exudyn filling in its defaults for the
rest.  Exudyn turns an item-interface object into the full dictionary of every field before it
reads it, so an item added this way costs about a third (measured with Exudyn 1.13.6: 30 against
79 us for a node, body, marker and joint; ``tests/test_exudyn_items.py`` compares the items
Exudyn stores both ways for every cell kind and mechanism built).  The builder adds some fifty
items for a small mechanism and the cell choice and the design studies build many.
"""

from __future__ import annotations

from typing import Any

from exudyn import itemInterface

__all__ = ["ii", "ItemFactory"]

#: the first field an item interface yields, by the prefix of its class name
_TYPE_PREFIX = ("Node", "Object", "Marker", "Load", "Sensor")


class ItemFactory:
    """The short dictionary of one Exudyn item type (called with the item interface's keywords)."""

    __slots__ = ("interface", "type_key", "type_name", "fields")

    def __init__(self, name: str) -> None:
        #: the item interface's class name (``"ObjectJointRevolute2D"``)
        self.interface = name
        interface = getattr(itemInterface, name)
        self.type_key, self.type_name = next(iter(interface()))  # e.g. ("objectType", "JointRevolute2D")
        #: the keywords the item interface takes (a misspelt one is refused here, as the interface would)
        self.fields = frozenset(interface.__init__.__code__.co_varnames[1:interface.__init__.__code__.co_argcount])

    def __call__(self, **fields: Any) -> dict:
        item = {self.type_key: self.type_name}
        for key, value in fields.items():
            if key == "visualization":
                for v_key, v_value in value.items():
                    item["V" + v_key] = v_value
            elif key in self.fields:
                item[key] = value
            else:
                raise TypeError(f"{self.type_name}: unexpected keyword {key!r} (Exudyn's item interface takes "
                                f"{', '.join(sorted(self.fields))})")
        return item


class _Items:
    """``ii.<ItemInterfaceName>``: an :class:`ItemFactory`, made on first use."""

    def __getattr__(self, name: str) -> ItemFactory:
        if not name.startswith(_TYPE_PREFIX) or not hasattr(itemInterface, name):
            raise AttributeError(f"exudyn.itemInterface has no item {name!r}")
        factory = ItemFactory(name)
        setattr(self, name, factory)
        return factory


#: the item types by their ``exudyn.itemInterface`` names (``ii.NodeRigidBody2D(...)``), as short dictionaries
ii = _Items()
