"""Makes a native submodule's names the public names of a package module."""

import types


def reexport(native, namespace, module_name):
    """Copies the public names of `native` into `namespace` (a module's globals()), and gives its
    classes `module_name` as their home, so help(), repr and pickling name the public module."""
    public = [name for name in dir(native)
              if not name.startswith("_") and not isinstance(getattr(native, name), types.ModuleType)]
    for name in public:
        value = getattr(native, name)
        if isinstance(value, type):
            value.__module__ = module_name
        namespace[name] = value
    return public
