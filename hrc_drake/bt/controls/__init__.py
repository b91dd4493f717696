"""Built-in control nodes, following BehaviorTree.CPP 4.x (src/controls): sequences and
fallbacks (:mod:`.sequences`), parallels (:mod:`.parallel`) and branches chosen by a
condition or a value (:mod:`.branches`)."""
