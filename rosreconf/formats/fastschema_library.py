"""fastjsonschema's code for component-library.schema.json: written by
scripts/fast_validators.py, do not edit (see structure.fast_validator).
"""

# ruff: noqa
# fmt: off
# mypy: ignore-errors
SOURCE = 'f080f95ed9b62a4219da8b0f8cae30f6c5b8fdd71833cdfc7a3afc3f796fe74e'
VERSION = "2.22.3"
from decimal import Decimal
import re
from fastjsonschema import JsonSchemaValueException, JsonSchemaValuesException


REGEX_PATTERNS = {
    '^[A-Za-z0-9_.\\-]+$': re.compile('^[A-Za-z0-9_.\\-]+\\Z'),
    '^/?[A-Za-z][A-Za-z0-9_]*(/[A-Za-z][A-Za-z0-9_]*)*$': re.compile('^/?[A-Za-z][A-Za-z0-9_]*(/[A-Za-z][A-Za-z0-9_]*)*\\Z'),
    '^[A-Za-z][A-Za-z0-9_]*/[A-Za-z][A-Za-z0-9_]*$': re.compile('^[A-Za-z][A-Za-z0-9_]*/[A-Za-z][A-Za-z0-9_]*\\Z'),
    '^[A-Za-z][A-Za-z0-9_]*$': re.compile('^[A-Za-z][A-Za-z0-9_]*\\Z')
}

NoneType = type(None)

def validate_urn_rosreconf_component_library_1(data, custom_formats={}, name_prefix=None):
    if not isinstance(data, (dict)):
        raise JsonSchemaValueException("" + (name_prefix or "data") + " must be object", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='type')
    data_is_dict = isinstance(data, dict)
    if data_is_dict:
        data__missing_keys = set(['format', 'version', 'name', 'components']) - data.keys()
        if data__missing_keys:
            raise JsonSchemaValueException("" + (name_prefix or "data") + " must contain " + (str(sorted(data__missing_keys)) + " properties"), value=data, name="" + (name_prefix or "data") + "", definition=None, rule='required')
        data_keys = set(data.keys())
        if "format" in data_keys:
            data_keys.remove("format")
            data__format = data["format"]
            if not (isinstance(data__format, str) and data__format == 'rosreconf/component-library'):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".format must be same as const definition: rosreconf/component-library", value=data__format, name="" + (name_prefix or "data") + ".format", definition=None, rule='const')
        if "version" in data_keys:
            data_keys.remove("version")
            data__version = data["version"]
            if not (isinstance(data__version, (int, float)) and not isinstance(data__version, bool) and data__version == 1):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".version must be same as const definition: 1", value=data__version, name="" + (name_prefix or "data") + ".version", definition=None, rule='const')
        if "name" in data_keys:
            data_keys.remove("name")
            data__name = data["name"]
            validate____defs_name(data__name, custom_formats, (name_prefix or "data") + ".name")
        if "description" in data_keys:
            data_keys.remove("description")
            data__description = data["description"]
            if not isinstance(data__description, (str)):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".description must be string", value=data__description, name="" + (name_prefix or "data") + ".description", definition=None, rule='type')
        if "components" in data_keys:
            data_keys.remove("components")
            data__components = data["components"]
            if not isinstance(data__components, (list, tuple)):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".components must be array", value=data__components, name="" + (name_prefix or "data") + ".components", definition=None, rule='type')
            data__components_is_list = isinstance(data__components, (list, tuple))
            if data__components_is_list:
                data__components_len = len(data__components)
                if data__components_len < 1:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".components must contain at least 1 items", value=data__components, name="" + (name_prefix or "data") + ".components", definition=None, rule='minItems')
                for data__components_x, data__components_item in enumerate(data__components):
                    validate____defs_component(data__components_item, custom_formats, (name_prefix or "data"))
        if data_keys:
            raise JsonSchemaValueException("" + (name_prefix or "data") + " must not contain "+str(data_keys)+" properties", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='additionalProperties')
    return data

def validate____defs_component(data, custom_formats={}, name_prefix=None):
    if not isinstance(data, (dict)):
        raise JsonSchemaValueException("" + (name_prefix or "data") + " must be object", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='type')
    data_is_dict = isinstance(data, dict)
    if data_is_dict:
        data__missing_keys = set(['name', 'abstraction']) - data.keys()
        if data__missing_keys:
            raise JsonSchemaValueException("" + (name_prefix or "data") + " must contain " + (str(sorted(data__missing_keys)) + " properties"), value=data, name="" + (name_prefix or "data") + "", definition=None, rule='required')
        data_keys = set(data.keys())
        if "name" in data_keys:
            data_keys.remove("name")
            data__name = data["name"]
            validate____defs_name(data__name, custom_formats, (name_prefix or "data") + ".name")
        if "abstraction" in data_keys:
            data_keys.remove("abstraction")
            data__abstraction = data["abstraction"]
            validate____defs_name(data__abstraction, custom_formats, (name_prefix or "data") + ".abstraction")
        if "description" in data_keys:
            data_keys.remove("description")
            data__description = data["description"]
            if not isinstance(data__description, (str)):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".description must be string", value=data__description, name="" + (name_prefix or "data") + ".description", definition=None, rule='type')
        if "provides" in data_keys:
            data_keys.remove("provides")
            data__provides = data["provides"]
            if not isinstance(data__provides, (list, tuple)):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".provides must be array", value=data__provides, name="" + (name_prefix or "data") + ".provides", definition=None, rule='type')
            data__provides_is_list = isinstance(data__provides, (list, tuple))
            if data__provides_is_list:
                data__provides_len = len(data__provides)
                for data__provides_x, data__provides_item in enumerate(data__provides):
                    validate____defs_interface(data__provides_item, custom_formats, (name_prefix or "data"))
        if "requires" in data_keys:
            data_keys.remove("requires")
            data__requires = data["requires"]
            if not isinstance(data__requires, (list, tuple)):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".requires must be array", value=data__requires, name="" + (name_prefix or "data") + ".requires", definition=None, rule='type')
            data__requires_is_list = isinstance(data__requires, (list, tuple))
            if data__requires_is_list:
                data__requires_len = len(data__requires)
                for data__requires_x, data__requires_item in enumerate(data__requires):
                    validate____defs_requirement(data__requires_item, custom_formats, (name_prefix or "data"))
        if "failure_probability" in data_keys:
            data_keys.remove("failure_probability")
            data__failureprobability = data["failure_probability"]
            if not isinstance(data__failureprobability, (int, float, Decimal)) or isinstance(data__failureprobability, bool):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".failure_probability must be number", value=data__failureprobability, name="" + (name_prefix or "data") + ".failure_probability", definition=None, rule='type')
            if isinstance(data__failureprobability, (int, float, Decimal)) and not isinstance(data__failureprobability, bool):
                if data__failureprobability < 0:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".failure_probability must be bigger than or equal to 0", value=data__failureprobability, name="" + (name_prefix or "data") + ".failure_probability", definition=None, rule='minimum')
                if data__failureprobability > 1:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".failure_probability must be smaller than or equal to 1", value=data__failureprobability, name="" + (name_prefix or "data") + ".failure_probability", definition=None, rule='maximum')
        if "needs" in data_keys:
            data_keys.remove("needs")
            data__needs = data["needs"]
            if not isinstance(data__needs, (list, tuple)):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".needs must be array", value=data__needs, name="" + (name_prefix or "data") + ".needs", definition=None, rule='type')
            data__needs_is_list = isinstance(data__needs, (list, tuple))
            if data__needs_is_list:
                def fn(var): return frozenset(dict((k, fn(v)) for k, v in var.items()).items()) if hasattr(var, "items") else tuple(fn(v) for v in var) if isinstance(var, (dict, list)) else (bool, var) if isinstance(var, bool) else var
                data__needs_len = len(data__needs)
                if data__needs_len > len(set(fn(data__needs_x) for data__needs_x in data__needs)):
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".needs must contain unique items", value=data__needs, name="" + (name_prefix or "data") + ".needs", definition=None, rule='uniqueItems')
                for data__needs_x, data__needs_item in enumerate(data__needs):
                    validate____defs_name(data__needs_item, custom_formats, (name_prefix or "data"))
        if "excludes" in data_keys:
            data_keys.remove("excludes")
            data__excludes = data["excludes"]
            if not isinstance(data__excludes, (list, tuple)):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".excludes must be array", value=data__excludes, name="" + (name_prefix or "data") + ".excludes", definition=None, rule='type')
            data__excludes_is_list = isinstance(data__excludes, (list, tuple))
            if data__excludes_is_list:
                def fn(var): return frozenset(dict((k, fn(v)) for k, v in var.items()).items()) if hasattr(var, "items") else tuple(fn(v) for v in var) if isinstance(var, (dict, list)) else (bool, var) if isinstance(var, bool) else var
                data__excludes_len = len(data__excludes)
                if data__excludes_len > len(set(fn(data__excludes_x) for data__excludes_x in data__excludes)):
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".excludes must contain unique items", value=data__excludes, name="" + (name_prefix or "data") + ".excludes", definition=None, rule='uniqueItems')
                for data__excludes_x, data__excludes_item in enumerate(data__excludes):
                    validate____defs_name(data__excludes_item, custom_formats, (name_prefix or "data"))
        if "schemas" in data_keys:
            data_keys.remove("schemas")
            data__schemas = data["schemas"]
            if not isinstance(data__schemas, (list, tuple)):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".schemas must be array", value=data__schemas, name="" + (name_prefix or "data") + ".schemas", definition=None, rule='type')
            data__schemas_is_list = isinstance(data__schemas, (list, tuple))
            if data__schemas_is_list:
                def fn(var): return frozenset(dict((k, fn(v)) for k, v in var.items()).items()) if hasattr(var, "items") else tuple(fn(v) for v in var) if isinstance(var, (dict, list)) else (bool, var) if isinstance(var, bool) else var
                data__schemas_len = len(data__schemas)
                if data__schemas_len > len(set(fn(data__schemas_x) for data__schemas_x in data__schemas)):
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".schemas must contain unique items", value=data__schemas, name="" + (name_prefix or "data") + ".schemas", definition=None, rule='uniqueItems')
                for data__schemas_x, data__schemas_item in enumerate(data__schemas):
                    validate____defs_name(data__schemas_item, custom_formats, (name_prefix or "data"))
        if "ros" in data_keys:
            data_keys.remove("ros")
            data__ros = data["ros"]
            if not isinstance(data__ros, (dict)):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".ros must be object", value=data__ros, name="" + (name_prefix or "data") + ".ros", definition=None, rule='type')
            data__ros_is_dict = isinstance(data__ros, dict)
            if data__ros_is_dict:
                data__ros__missing_keys = set(['package', 'executable']) - data__ros.keys()
                if data__ros__missing_keys:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".ros must contain " + (str(sorted(data__ros__missing_keys)) + " properties"), value=data__ros, name="" + (name_prefix or "data") + ".ros", definition=None, rule='required')
                data__ros_keys = set(data__ros.keys())
                if "package" in data__ros_keys:
                    data__ros_keys.remove("package")
                    data__ros__package = data__ros["package"]
                    validate____defs_name(data__ros__package, custom_formats, (name_prefix or "data") + ".ros.package")
                if "executable" in data__ros_keys:
                    data__ros_keys.remove("executable")
                    data__ros__executable = data__ros["executable"]
                    if not isinstance(data__ros__executable, (str)):
                        raise JsonSchemaValueException("" + (name_prefix or "data") + ".ros.executable must be string", value=data__ros__executable, name="" + (name_prefix or "data") + ".ros.executable", definition=None, rule='type')
                    if isinstance(data__ros__executable, str):
                        if not REGEX_PATTERNS['^[A-Za-z0-9_.\\-]+$'].search(data__ros__executable):
                            raise JsonSchemaValueException("" + (name_prefix or "data") + ".ros.executable must match pattern ^[A-Za-z0-9_.\\-]+$", value=data__ros__executable, name="" + (name_prefix or "data") + ".ros.executable", definition=None, rule='pattern')
                if "namespace" in data__ros_keys:
                    data__ros_keys.remove("namespace")
                    data__ros__namespace = data__ros["namespace"]
                    validate____defs_label(data__ros__namespace, custom_formats, (name_prefix or "data") + ".ros.namespace")
                if "node" in data__ros_keys:
                    data__ros_keys.remove("node")
                    data__ros__node = data__ros["node"]
                    validate____defs_name(data__ros__node, custom_formats, (name_prefix or "data") + ".ros.node")
                if "parameters" in data__ros_keys:
                    data__ros_keys.remove("parameters")
                    data__ros__parameters = data__ros["parameters"]
                    if not isinstance(data__ros__parameters, (dict)):
                        raise JsonSchemaValueException("" + (name_prefix or "data") + ".ros.parameters must be object", value=data__ros__parameters, name="" + (name_prefix or "data") + ".ros.parameters", definition=None, rule='type')
                    data__ros__parameters_is_dict = isinstance(data__ros__parameters, dict)
                    if data__ros__parameters_is_dict:
                        data__ros__parameters_keys = set(data__ros__parameters.keys())
                        for data__ros__parameters_key in data__ros__parameters_keys:
                            if data__ros__parameters_key not in []:
                                data__ros__parameters_value = data__ros__parameters.get(data__ros__parameters_key)
                                data__ros__parameters_value_any_of_count1 = 0
                                if not data__ros__parameters_value_any_of_count1:
                                    try:
                                        validate____defs_scalar(data__ros__parameters_value, custom_formats, (name_prefix or "data"))
                                        data__ros__parameters_value_any_of_count1 += 1
                                    except (JsonSchemaValueException, JsonSchemaValuesException): pass
                                if not data__ros__parameters_value_any_of_count1:
                                    try:
                                        if not isinstance(data__ros__parameters_value, (dict)):
                                            raise JsonSchemaValueException("" + (name_prefix or "data") + " must be object", value=data__ros__parameters_value, name="" + (name_prefix or "data") + "", definition=None, rule='type')
                                        data__ros__parameters_value_is_dict = isinstance(data__ros__parameters_value, dict)
                                        if data__ros__parameters_value_is_dict:
                                            data__ros__parameters_value__missing_keys = set(['substitution']) - data__ros__parameters_value.keys()
                                            if data__ros__parameters_value__missing_keys:
                                                raise JsonSchemaValueException("" + (name_prefix or "data") + " must contain " + (str(sorted(data__ros__parameters_value__missing_keys)) + " properties"), value=data__ros__parameters_value, name="" + (name_prefix or "data") + "", definition=None, rule='required')
                                            data__ros__parameters_value_keys = set(data__ros__parameters_value.keys())
                                            if "substitution" in data__ros__parameters_value_keys:
                                                data__ros__parameters_value_keys.remove("substitution")
                                                data__ros__parameters_value__substitution = data__ros__parameters_value["substitution"]
                                                if not isinstance(data__ros__parameters_value__substitution, (str)):
                                                    raise JsonSchemaValueException("" + (name_prefix or "data") + " must be string", value=data__ros__parameters_value__substitution, name="" + (name_prefix or "data") + "", definition=None, rule='type')
                                                if isinstance(data__ros__parameters_value__substitution, str):
                                                    data__ros__parameters_value__substitution_len = len(data__ros__parameters_value__substitution)
                                                    if data__ros__parameters_value__substitution_len < 1:
                                                        raise JsonSchemaValueException("" + (name_prefix or "data") + " must be longer than or equal to 1 characters", value=data__ros__parameters_value__substitution, name="" + (name_prefix or "data") + "", definition=None, rule='minLength')
                                            if data__ros__parameters_value_keys:
                                                raise JsonSchemaValueException("" + (name_prefix or "data") + " must not contain "+str(data__ros__parameters_value_keys)+" properties", value=data__ros__parameters_value, name="" + (name_prefix or "data") + "", definition=None, rule='additionalProperties')
                                        data__ros__parameters_value_any_of_count1 += 1
                                    except (JsonSchemaValueException, JsonSchemaValuesException): pass
                                if not data__ros__parameters_value_any_of_count1:
                                    raise JsonSchemaValueException("" + (name_prefix or "data") + " cannot be validated by any definition", value=data__ros__parameters_value, name="" + (name_prefix or "data") + "", definition=None, rule='anyOf')
                        data__ros__parameters_len = len(data__ros__parameters)
                        if data__ros__parameters_len != 0:
                            data__ros__parameters_property_names = True
                            for data__ros__parameters_key in data__ros__parameters:
                                try:
                                    validate____defs_name(data__ros__parameters_key, custom_formats, (name_prefix or "data") + ".ros.parameters")
                                except (JsonSchemaValueException, JsonSchemaValuesException):
                                    data__ros__parameters_property_names = False
                            if not data__ros__parameters_property_names:
                                raise JsonSchemaValueException("" + (name_prefix or "data") + ".ros.parameters must be named by propertyName definition", value=data__ros__parameters, name="" + (name_prefix or "data") + ".ros.parameters", definition=None, rule='propertyNames')
                if "remappings" in data__ros_keys:
                    data__ros_keys.remove("remappings")
                    data__ros__remappings = data__ros["remappings"]
                    if not isinstance(data__ros__remappings, (dict)):
                        raise JsonSchemaValueException("" + (name_prefix or "data") + ".ros.remappings must be object", value=data__ros__remappings, name="" + (name_prefix or "data") + ".ros.remappings", definition=None, rule='type')
                    data__ros__remappings_is_dict = isinstance(data__ros__remappings, dict)
                    if data__ros__remappings_is_dict:
                        data__ros__remappings_keys = set(data__ros__remappings.keys())
                        for data__ros__remappings_key in data__ros__remappings_keys:
                            if data__ros__remappings_key not in []:
                                data__ros__remappings_value = data__ros__remappings.get(data__ros__remappings_key)
                                validate____defs_label(data__ros__remappings_value, custom_formats, (name_prefix or "data"))
                        data__ros__remappings_len = len(data__ros__remappings)
                        if data__ros__remappings_len != 0:
                            data__ros__remappings_property_names = True
                            for data__ros__remappings_key in data__ros__remappings:
                                try:
                                    validate____defs_label(data__ros__remappings_key, custom_formats, (name_prefix or "data") + ".ros.remappings")
                                except (JsonSchemaValueException, JsonSchemaValuesException):
                                    data__ros__remappings_property_names = False
                            if not data__ros__remappings_property_names:
                                raise JsonSchemaValueException("" + (name_prefix or "data") + ".ros.remappings must be named by propertyName definition", value=data__ros__remappings, name="" + (name_prefix or "data") + ".ros.remappings", definition=None, rule='propertyNames')
                if "lifecycle" in data__ros_keys:
                    data__ros_keys.remove("lifecycle")
                    data__ros__lifecycle = data__ros["lifecycle"]
                    if not isinstance(data__ros__lifecycle, (bool)):
                        raise JsonSchemaValueException("" + (name_prefix or "data") + ".ros.lifecycle must be boolean", value=data__ros__lifecycle, name="" + (name_prefix or "data") + ".ros.lifecycle", definition=None, rule='type')
                if "args" in data__ros_keys:
                    data__ros_keys.remove("args")
                    data__ros__args = data__ros["args"]
                    if not isinstance(data__ros__args, (list, tuple)):
                        raise JsonSchemaValueException("" + (name_prefix or "data") + ".ros.args must be array", value=data__ros__args, name="" + (name_prefix or "data") + ".ros.args", definition=None, rule='type')
                    data__ros__args_is_list = isinstance(data__ros__args, (list, tuple))
                    if data__ros__args_is_list:
                        data__ros__args_len = len(data__ros__args)
                        for data__ros__args_x, data__ros__args_item in enumerate(data__ros__args):
                            if not isinstance(data__ros__args_item, (str)):
                                raise JsonSchemaValueException("" + (name_prefix or "data") + " must be string", value=data__ros__args_item, name="" + (name_prefix or "data") + "", definition=None, rule='type')
                if data__ros_keys:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".ros must not contain "+str(data__ros_keys)+" properties", value=data__ros, name="" + (name_prefix or "data") + ".ros", definition=None, rule='additionalProperties')
        if "metrics" in data_keys:
            data_keys.remove("metrics")
            data__metrics = data["metrics"]
            if not isinstance(data__metrics, (dict)):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".metrics must be object", value=data__metrics, name="" + (name_prefix or "data") + ".metrics", definition=None, rule='type')
            data__metrics_is_dict = isinstance(data__metrics, dict)
            if data__metrics_is_dict:
                data__metrics_keys = set(data__metrics.keys())
                for data__metrics_key in data__metrics_keys:
                    if data__metrics_key not in []:
                        data__metrics_value = data__metrics.get(data__metrics_key)
                        if not isinstance(data__metrics_value, (int, float, Decimal)) or isinstance(data__metrics_value, bool):
                            raise JsonSchemaValueException("" + (name_prefix or "data") + " must be number", value=data__metrics_value, name="" + (name_prefix or "data") + "", definition=None, rule='type')
                data__metrics_len = len(data__metrics)
                if data__metrics_len != 0:
                    data__metrics_property_names = True
                    for data__metrics_key in data__metrics:
                        try:
                            validate____defs_name(data__metrics_key, custom_formats, (name_prefix or "data") + ".metrics")
                        except (JsonSchemaValueException, JsonSchemaValuesException):
                            data__metrics_property_names = False
                    if not data__metrics_property_names:
                        raise JsonSchemaValueException("" + (name_prefix or "data") + ".metrics must be named by propertyName definition", value=data__metrics, name="" + (name_prefix or "data") + ".metrics", definition=None, rule='propertyNames')
        if "dynamics" in data_keys:
            data_keys.remove("dynamics")
            data__dynamics = data["dynamics"]
            validate____defs_dynamics(data__dynamics, custom_formats, (name_prefix or "data") + ".dynamics")
        if data_keys:
            raise JsonSchemaValueException("" + (name_prefix or "data") + " must not contain "+str(data_keys)+" properties", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='additionalProperties')
    return data

def validate____defs_dynamics(data, custom_formats={}, name_prefix=None):
    if not isinstance(data, (dict)):
        raise JsonSchemaValueException("" + (name_prefix or "data") + " must be object", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='type')
    data_any_of_count2 = 0
    if not data_any_of_count2:
        try:
            data_is_dict = isinstance(data, dict)
            if data_is_dict:
                data__missing_keys = set(['transfer_function']) - data.keys()
                if data__missing_keys:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + " must contain " + (str(sorted(data__missing_keys)) + " properties"), value=data, name="" + (name_prefix or "data") + "", definition=None, rule='required')
            data_any_of_count2 += 1
        except (JsonSchemaValueException, JsonSchemaValuesException): pass
    if not data_any_of_count2:
        try:
            data_is_dict = isinstance(data, dict)
            if data_is_dict:
                data__missing_keys = set(['state_space']) - data.keys()
                if data__missing_keys:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + " must contain " + (str(sorted(data__missing_keys)) + " properties"), value=data, name="" + (name_prefix or "data") + "", definition=None, rule='required')
            data_any_of_count2 += 1
        except (JsonSchemaValueException, JsonSchemaValuesException): pass
    if not data_any_of_count2:
        raise JsonSchemaValueException("" + (name_prefix or "data") + " cannot be validated by any definition", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='anyOf')
    data_is_dict = isinstance(data, dict)
    if data_is_dict:
        if "transfer_function" in data:
            data_is_dict = isinstance(data, dict)
            if data_is_dict:
                data_keys = set(data.keys())
                if "state_space" in data_keys:
                    data_keys.remove("state_space")
                    data__statespace = data["state_space"]
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".state_space must not be there", value=data__statespace, name="" + (name_prefix or "data") + ".state_space", definition=False, rule=None)
        if "state_space" in data:
            data_is_dict = isinstance(data, dict)
            if data_is_dict:
                data_keys = set(data.keys())
                if "transfer_function" in data_keys:
                    data_keys.remove("transfer_function")
                    data__transferfunction = data["transfer_function"]
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".transfer_function must not be there", value=data__transferfunction, name="" + (name_prefix or "data") + ".transfer_function", definition=False, rule=None)
        data_keys = set(data.keys())
        if "transfer_function" in data_keys:
            data_keys.remove("transfer_function")
            data__transferfunction = data["transfer_function"]
            if not isinstance(data__transferfunction, (dict)):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".transfer_function must be object", value=data__transferfunction, name="" + (name_prefix or "data") + ".transfer_function", definition=None, rule='type')
            data__transferfunction_is_dict = isinstance(data__transferfunction, dict)
            if data__transferfunction_is_dict:
                data__transferfunction__missing_keys = set(['num', 'den']) - data__transferfunction.keys()
                if data__transferfunction__missing_keys:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".transfer_function must contain " + (str(sorted(data__transferfunction__missing_keys)) + " properties"), value=data__transferfunction, name="" + (name_prefix or "data") + ".transfer_function", definition=None, rule='required')
                data__transferfunction_keys = set(data__transferfunction.keys())
                if "num" in data__transferfunction_keys:
                    data__transferfunction_keys.remove("num")
                    data__transferfunction__num = data__transferfunction["num"]
                    if not isinstance(data__transferfunction__num, (list, tuple)):
                        raise JsonSchemaValueException("" + (name_prefix or "data") + ".transfer_function.num must be array", value=data__transferfunction__num, name="" + (name_prefix or "data") + ".transfer_function.num", definition=None, rule='type')
                    data__transferfunction__num_is_list = isinstance(data__transferfunction__num, (list, tuple))
                    if data__transferfunction__num_is_list:
                        data__transferfunction__num_len = len(data__transferfunction__num)
                        if data__transferfunction__num_len < 1:
                            raise JsonSchemaValueException("" + (name_prefix or "data") + ".transfer_function.num must contain at least 1 items", value=data__transferfunction__num, name="" + (name_prefix or "data") + ".transfer_function.num", definition=None, rule='minItems')
                        for data__transferfunction__num_x, data__transferfunction__num_item in enumerate(data__transferfunction__num):
                            if not isinstance(data__transferfunction__num_item, (int, float, Decimal)) or isinstance(data__transferfunction__num_item, bool):
                                raise JsonSchemaValueException("" + (name_prefix or "data") + " must be number", value=data__transferfunction__num_item, name="" + (name_prefix or "data") + "", definition=None, rule='type')
                if "den" in data__transferfunction_keys:
                    data__transferfunction_keys.remove("den")
                    data__transferfunction__den = data__transferfunction["den"]
                    if not isinstance(data__transferfunction__den, (list, tuple)):
                        raise JsonSchemaValueException("" + (name_prefix or "data") + ".transfer_function.den must be array", value=data__transferfunction__den, name="" + (name_prefix or "data") + ".transfer_function.den", definition=None, rule='type')
                    data__transferfunction__den_is_list = isinstance(data__transferfunction__den, (list, tuple))
                    if data__transferfunction__den_is_list:
                        data__transferfunction__den_len = len(data__transferfunction__den)
                        if data__transferfunction__den_len < 1:
                            raise JsonSchemaValueException("" + (name_prefix or "data") + ".transfer_function.den must contain at least 1 items", value=data__transferfunction__den, name="" + (name_prefix or "data") + ".transfer_function.den", definition=None, rule='minItems')
                        for data__transferfunction__den_x, data__transferfunction__den_item in enumerate(data__transferfunction__den):
                            if not isinstance(data__transferfunction__den_item, (int, float, Decimal)) or isinstance(data__transferfunction__den_item, bool):
                                raise JsonSchemaValueException("" + (name_prefix or "data") + " must be number", value=data__transferfunction__den_item, name="" + (name_prefix or "data") + "", definition=None, rule='type')
                if data__transferfunction_keys:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".transfer_function must not contain "+str(data__transferfunction_keys)+" properties", value=data__transferfunction, name="" + (name_prefix or "data") + ".transfer_function", definition=None, rule='additionalProperties')
        if "state_space" in data_keys:
            data_keys.remove("state_space")
            data__statespace = data["state_space"]
            if not isinstance(data__statespace, (dict)):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".state_space must be object", value=data__statespace, name="" + (name_prefix or "data") + ".state_space", definition=None, rule='type')
            data__statespace_is_dict = isinstance(data__statespace, dict)
            if data__statespace_is_dict:
                data__statespace__missing_keys = set(['A', 'B', 'C', 'D']) - data__statespace.keys()
                if data__statespace__missing_keys:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".state_space must contain " + (str(sorted(data__statespace__missing_keys)) + " properties"), value=data__statespace, name="" + (name_prefix or "data") + ".state_space", definition=None, rule='required')
                data__statespace_keys = set(data__statespace.keys())
                if "A" in data__statespace_keys:
                    data__statespace_keys.remove("A")
                    data__statespace__A = data__statespace["A"]
                    if not isinstance(data__statespace__A, (list, tuple)):
                        raise JsonSchemaValueException("" + (name_prefix or "data") + ".state_space.A must be array", value=data__statespace__A, name="" + (name_prefix or "data") + ".state_space.A", definition=None, rule='type')
                    data__statespace__A_is_list = isinstance(data__statespace__A, (list, tuple))
                    if data__statespace__A_is_list:
                        data__statespace__A_len = len(data__statespace__A)
                        if data__statespace__A_len < 1:
                            raise JsonSchemaValueException("" + (name_prefix or "data") + ".state_space.A must contain at least 1 items", value=data__statespace__A, name="" + (name_prefix or "data") + ".state_space.A", definition=None, rule='minItems')
                        for data__statespace__A_x, data__statespace__A_item in enumerate(data__statespace__A):
                            if not isinstance(data__statespace__A_item, (list, tuple)):
                                raise JsonSchemaValueException("" + (name_prefix or "data") + " must be array", value=data__statespace__A_item, name="" + (name_prefix or "data") + "", definition=None, rule='type')
                            data__statespace__A_item_is_list = isinstance(data__statespace__A_item, (list, tuple))
                            if data__statespace__A_item_is_list:
                                data__statespace__A_item_len = len(data__statespace__A_item)
                                if data__statespace__A_item_len < 1:
                                    raise JsonSchemaValueException("" + (name_prefix or "data") + " must contain at least 1 items", value=data__statespace__A_item, name="" + (name_prefix or "data") + "", definition=None, rule='minItems')
                                for data__statespace__A_item_x, data__statespace__A_item_item in enumerate(data__statespace__A_item):
                                    if not isinstance(data__statespace__A_item_item, (int, float, Decimal)) or isinstance(data__statespace__A_item_item, bool):
                                        raise JsonSchemaValueException("" + (name_prefix or "data") + " must be number", value=data__statespace__A_item_item, name="" + (name_prefix or "data") + "", definition=None, rule='type')
                if "B" in data__statespace_keys:
                    data__statespace_keys.remove("B")
                    data__statespace__B = data__statespace["B"]
                    if not isinstance(data__statespace__B, (list, tuple)):
                        raise JsonSchemaValueException("" + (name_prefix or "data") + ".state_space.B must be array", value=data__statespace__B, name="" + (name_prefix or "data") + ".state_space.B", definition=None, rule='type')
                    data__statespace__B_is_list = isinstance(data__statespace__B, (list, tuple))
                    if data__statespace__B_is_list:
                        data__statespace__B_len = len(data__statespace__B)
                        if data__statespace__B_len < 1:
                            raise JsonSchemaValueException("" + (name_prefix or "data") + ".state_space.B must contain at least 1 items", value=data__statespace__B, name="" + (name_prefix or "data") + ".state_space.B", definition=None, rule='minItems')
                        for data__statespace__B_x, data__statespace__B_item in enumerate(data__statespace__B):
                            if not isinstance(data__statespace__B_item, (list, tuple)):
                                raise JsonSchemaValueException("" + (name_prefix or "data") + " must be array", value=data__statespace__B_item, name="" + (name_prefix or "data") + "", definition=None, rule='type')
                            data__statespace__B_item_is_list = isinstance(data__statespace__B_item, (list, tuple))
                            if data__statespace__B_item_is_list:
                                data__statespace__B_item_len = len(data__statespace__B_item)
                                if data__statespace__B_item_len < 1:
                                    raise JsonSchemaValueException("" + (name_prefix or "data") + " must contain at least 1 items", value=data__statespace__B_item, name="" + (name_prefix or "data") + "", definition=None, rule='minItems')
                                for data__statespace__B_item_x, data__statespace__B_item_item in enumerate(data__statespace__B_item):
                                    if not isinstance(data__statespace__B_item_item, (int, float, Decimal)) or isinstance(data__statespace__B_item_item, bool):
                                        raise JsonSchemaValueException("" + (name_prefix or "data") + " must be number", value=data__statespace__B_item_item, name="" + (name_prefix or "data") + "", definition=None, rule='type')
                if "C" in data__statespace_keys:
                    data__statespace_keys.remove("C")
                    data__statespace__C = data__statespace["C"]
                    if not isinstance(data__statespace__C, (list, tuple)):
                        raise JsonSchemaValueException("" + (name_prefix or "data") + ".state_space.C must be array", value=data__statespace__C, name="" + (name_prefix or "data") + ".state_space.C", definition=None, rule='type')
                    data__statespace__C_is_list = isinstance(data__statespace__C, (list, tuple))
                    if data__statespace__C_is_list:
                        data__statespace__C_len = len(data__statespace__C)
                        if data__statespace__C_len < 1:
                            raise JsonSchemaValueException("" + (name_prefix or "data") + ".state_space.C must contain at least 1 items", value=data__statespace__C, name="" + (name_prefix or "data") + ".state_space.C", definition=None, rule='minItems')
                        for data__statespace__C_x, data__statespace__C_item in enumerate(data__statespace__C):
                            if not isinstance(data__statespace__C_item, (list, tuple)):
                                raise JsonSchemaValueException("" + (name_prefix or "data") + " must be array", value=data__statespace__C_item, name="" + (name_prefix or "data") + "", definition=None, rule='type')
                            data__statespace__C_item_is_list = isinstance(data__statespace__C_item, (list, tuple))
                            if data__statespace__C_item_is_list:
                                data__statespace__C_item_len = len(data__statespace__C_item)
                                if data__statespace__C_item_len < 1:
                                    raise JsonSchemaValueException("" + (name_prefix or "data") + " must contain at least 1 items", value=data__statespace__C_item, name="" + (name_prefix or "data") + "", definition=None, rule='minItems')
                                for data__statespace__C_item_x, data__statespace__C_item_item in enumerate(data__statespace__C_item):
                                    if not isinstance(data__statespace__C_item_item, (int, float, Decimal)) or isinstance(data__statespace__C_item_item, bool):
                                        raise JsonSchemaValueException("" + (name_prefix or "data") + " must be number", value=data__statespace__C_item_item, name="" + (name_prefix or "data") + "", definition=None, rule='type')
                if "D" in data__statespace_keys:
                    data__statespace_keys.remove("D")
                    data__statespace__D = data__statespace["D"]
                    if not isinstance(data__statespace__D, (list, tuple)):
                        raise JsonSchemaValueException("" + (name_prefix or "data") + ".state_space.D must be array", value=data__statespace__D, name="" + (name_prefix or "data") + ".state_space.D", definition=None, rule='type')
                    data__statespace__D_is_list = isinstance(data__statespace__D, (list, tuple))
                    if data__statespace__D_is_list:
                        data__statespace__D_len = len(data__statespace__D)
                        if data__statespace__D_len < 1:
                            raise JsonSchemaValueException("" + (name_prefix or "data") + ".state_space.D must contain at least 1 items", value=data__statespace__D, name="" + (name_prefix or "data") + ".state_space.D", definition=None, rule='minItems')
                        for data__statespace__D_x, data__statespace__D_item in enumerate(data__statespace__D):
                            if not isinstance(data__statespace__D_item, (list, tuple)):
                                raise JsonSchemaValueException("" + (name_prefix or "data") + " must be array", value=data__statespace__D_item, name="" + (name_prefix or "data") + "", definition=None, rule='type')
                            data__statespace__D_item_is_list = isinstance(data__statespace__D_item, (list, tuple))
                            if data__statespace__D_item_is_list:
                                data__statespace__D_item_len = len(data__statespace__D_item)
                                if data__statespace__D_item_len < 1:
                                    raise JsonSchemaValueException("" + (name_prefix or "data") + " must contain at least 1 items", value=data__statespace__D_item, name="" + (name_prefix or "data") + "", definition=None, rule='minItems')
                                for data__statespace__D_item_x, data__statespace__D_item_item in enumerate(data__statespace__D_item):
                                    if not isinstance(data__statespace__D_item_item, (int, float, Decimal)) or isinstance(data__statespace__D_item_item, bool):
                                        raise JsonSchemaValueException("" + (name_prefix or "data") + " must be number", value=data__statespace__D_item_item, name="" + (name_prefix or "data") + "", definition=None, rule='type')
                if data__statespace_keys:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".state_space must not contain "+str(data__statespace_keys)+" properties", value=data__statespace, name="" + (name_prefix or "data") + ".state_space", definition=None, rule='additionalProperties')
        if "delay" in data_keys:
            data_keys.remove("delay")
            data__delay = data["delay"]
            if not isinstance(data__delay, (int, float, Decimal)) or isinstance(data__delay, bool):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".delay must be number", value=data__delay, name="" + (name_prefix or "data") + ".delay", definition=None, rule='type')
            if isinstance(data__delay, (int, float, Decimal)) and not isinstance(data__delay, bool):
                if data__delay < 0:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".delay must be bigger than or equal to 0", value=data__delay, name="" + (name_prefix or "data") + ".delay", definition=None, rule='minimum')
        if data_keys:
            raise JsonSchemaValueException("" + (name_prefix or "data") + " must not contain "+str(data_keys)+" properties", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='additionalProperties')
    return data

def validate____defs_scalar(data, custom_formats={}, name_prefix=None):
    if not isinstance(data, (str, int, float, Decimal, bool)):
        raise JsonSchemaValueException("" + (name_prefix or "data") + " must be string or number or boolean", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='type')
    return data

def validate____defs_label(data, custom_formats={}, name_prefix=None):
    if not isinstance(data, (str)):
        raise JsonSchemaValueException("" + (name_prefix or "data") + " must be string", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='type')
    if isinstance(data, str):
        if not REGEX_PATTERNS['^/?[A-Za-z][A-Za-z0-9_]*(/[A-Za-z][A-Za-z0-9_]*)*$'].search(data):
            raise JsonSchemaValueException("" + (name_prefix or "data") + " must match pattern ^/?[A-Za-z][A-Za-z0-9_]*(/[A-Za-z][A-Za-z0-9_]*)*$", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='pattern')
    return data

def validate____defs_requirement(data, custom_formats={}, name_prefix=None):
    data_any_of_count3 = 0
    if not data_any_of_count3:
        try:
            validate____defs_interface(data, custom_formats, (name_prefix or "data") + "")
            data_any_of_count3 += 1
        except (JsonSchemaValueException, JsonSchemaValuesException): pass
    if not data_any_of_count3:
        try:
            if not isinstance(data, (dict)):
                raise JsonSchemaValueException("" + (name_prefix or "data") + " must be object", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='type')
            data_is_dict = isinstance(data, dict)
            if data_is_dict:
                data__missing_keys = set(['any_of']) - data.keys()
                if data__missing_keys:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + " must contain " + (str(sorted(data__missing_keys)) + " properties"), value=data, name="" + (name_prefix or "data") + "", definition=None, rule='required')
                data_keys = set(data.keys())
                if "any_of" in data_keys:
                    data_keys.remove("any_of")
                    data__anyof = data["any_of"]
                    if not isinstance(data__anyof, (list, tuple)):
                        raise JsonSchemaValueException("" + (name_prefix or "data") + ".any_of must be array", value=data__anyof, name="" + (name_prefix or "data") + ".any_of", definition=None, rule='type')
                    data__anyof_is_list = isinstance(data__anyof, (list, tuple))
                    if data__anyof_is_list:
                        data__anyof_len = len(data__anyof)
                        if data__anyof_len < 2:
                            raise JsonSchemaValueException("" + (name_prefix or "data") + ".any_of must contain at least 2 items", value=data__anyof, name="" + (name_prefix or "data") + ".any_of", definition=None, rule='minItems')
                        for data__anyof_x, data__anyof_item in enumerate(data__anyof):
                            validate____defs_interface(data__anyof_item, custom_formats, (name_prefix or "data"))
                if data_keys:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + " must not contain "+str(data_keys)+" properties", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='additionalProperties')
            data_any_of_count3 += 1
        except (JsonSchemaValueException, JsonSchemaValuesException): pass
    if not data_any_of_count3:
        raise JsonSchemaValueException("" + (name_prefix or "data") + " cannot be validated by any definition", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='anyOf')
    return data

def validate____defs_interface(data, custom_formats={}, name_prefix=None):
    if not isinstance(data, (dict)):
        raise JsonSchemaValueException("" + (name_prefix or "data") + " must be object", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='type')
    data_any_of_count4 = 0
    if not data_any_of_count4:
        try:
            data_is_dict = isinstance(data, dict)
            if data_is_dict:
                data__missing_keys = set(['topic']) - data.keys()
                if data__missing_keys:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + " must contain " + (str(sorted(data__missing_keys)) + " properties"), value=data, name="" + (name_prefix or "data") + "", definition=None, rule='required')
            data_any_of_count4 += 1
        except (JsonSchemaValueException, JsonSchemaValuesException): pass
    if not data_any_of_count4:
        try:
            data_is_dict = isinstance(data, dict)
            if data_is_dict:
                data__missing_keys = set(['service']) - data.keys()
                if data__missing_keys:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + " must contain " + (str(sorted(data__missing_keys)) + " properties"), value=data, name="" + (name_prefix or "data") + "", definition=None, rule='required')
            data_any_of_count4 += 1
        except (JsonSchemaValueException, JsonSchemaValuesException): pass
    if not data_any_of_count4:
        raise JsonSchemaValueException("" + (name_prefix or "data") + " cannot be validated by any definition", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='anyOf')
    data_is_dict = isinstance(data, dict)
    if data_is_dict:
        data__missing_keys = set(['type']) - data.keys()
        if data__missing_keys:
            raise JsonSchemaValueException("" + (name_prefix or "data") + " must contain " + (str(sorted(data__missing_keys)) + " properties"), value=data, name="" + (name_prefix or "data") + "", definition=None, rule='required')
        if "topic" in data:
            data_is_dict = isinstance(data, dict)
            if data_is_dict:
                data_keys = set(data.keys())
                if "service" in data_keys:
                    data_keys.remove("service")
                    data__service = data["service"]
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".service must not be there", value=data__service, name="" + (name_prefix or "data") + ".service", definition=False, rule=None)
        if "service" in data:
            data_is_dict = isinstance(data, dict)
            if data_is_dict:
                data_keys = set(data.keys())
                if "topic" in data_keys:
                    data_keys.remove("topic")
                    data__topic = data["topic"]
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".topic must not be there", value=data__topic, name="" + (name_prefix or "data") + ".topic", definition=False, rule=None)
        data_keys = set(data.keys())
        if "topic" in data_keys:
            data_keys.remove("topic")
            data__topic = data["topic"]
            validate____defs_label(data__topic, custom_formats, (name_prefix or "data") + ".topic")
        if "service" in data_keys:
            data_keys.remove("service")
            data__service = data["service"]
            validate____defs_label(data__service, custom_formats, (name_prefix or "data") + ".service")
        if "type" in data_keys:
            data_keys.remove("type")
            data__type = data["type"]
            validate____defs_rostype(data__type, custom_formats, (name_prefix or "data") + ".type")
        if "qos" in data_keys:
            data_keys.remove("qos")
            data__qos = data["qos"]
            validate____defs_qos(data__qos, custom_formats, (name_prefix or "data") + ".qos")
        if data_keys:
            raise JsonSchemaValueException("" + (name_prefix or "data") + " must not contain "+str(data_keys)+" properties", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='additionalProperties')
    return data

def validate____defs_qos(data, custom_formats={}, name_prefix=None):
    if not isinstance(data, (dict)):
        raise JsonSchemaValueException("" + (name_prefix or "data") + " must be object", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='type')
    data_is_dict = isinstance(data, dict)
    if data_is_dict:
        data_keys = set(data.keys())
        if "reliability" in data_keys:
            data_keys.remove("reliability")
            data__reliability = data["reliability"]
            if not (isinstance(data__reliability, str) and data__reliability == 'reliable' or isinstance(data__reliability, str) and data__reliability == 'best_effort'):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".reliability must be one of ['reliable', 'best_effort']", value=data__reliability, name="" + (name_prefix or "data") + ".reliability", definition=None, rule='enum')
        if "durability" in data_keys:
            data_keys.remove("durability")
            data__durability = data["durability"]
            if not (isinstance(data__durability, str) and data__durability == 'volatile' or isinstance(data__durability, str) and data__durability == 'transient_local'):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".durability must be one of ['volatile', 'transient_local']", value=data__durability, name="" + (name_prefix or "data") + ".durability", definition=None, rule='enum')
        if "deadline" in data_keys:
            data_keys.remove("deadline")
            data__deadline = data["deadline"]
            if not isinstance(data__deadline, (int, float, Decimal, NoneType)) or isinstance(data__deadline, bool):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".deadline must be number or null", value=data__deadline, name="" + (name_prefix or "data") + ".deadline", definition=None, rule='type')
            if isinstance(data__deadline, (int, float, Decimal)) and not isinstance(data__deadline, bool):
                if data__deadline <= 0:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".deadline must be bigger than 0", value=data__deadline, name="" + (name_prefix or "data") + ".deadline", definition=None, rule='exclusiveMinimum')
        if "liveliness" in data_keys:
            data_keys.remove("liveliness")
            data__liveliness = data["liveliness"]
            if not (isinstance(data__liveliness, str) and data__liveliness == 'automatic' or isinstance(data__liveliness, str) and data__liveliness == 'manual_by_topic'):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".liveliness must be one of ['automatic', 'manual_by_topic']", value=data__liveliness, name="" + (name_prefix or "data") + ".liveliness", definition=None, rule='enum')
        if "lease_duration" in data_keys:
            data_keys.remove("lease_duration")
            data__leaseduration = data["lease_duration"]
            if not isinstance(data__leaseduration, (int, float, Decimal, NoneType)) or isinstance(data__leaseduration, bool):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".lease_duration must be number or null", value=data__leaseduration, name="" + (name_prefix or "data") + ".lease_duration", definition=None, rule='type')
            if isinstance(data__leaseduration, (int, float, Decimal)) and not isinstance(data__leaseduration, bool):
                if data__leaseduration <= 0:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".lease_duration must be bigger than 0", value=data__leaseduration, name="" + (name_prefix or "data") + ".lease_duration", definition=None, rule='exclusiveMinimum')
        if "depth" in data_keys:
            data_keys.remove("depth")
            data__depth = data["depth"]
            if not isinstance(data__depth, (int)) and not (isinstance(data__depth, float) and data__depth.is_integer()) or isinstance(data__depth, bool):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".depth must be integer", value=data__depth, name="" + (name_prefix or "data") + ".depth", definition=None, rule='type')
            if isinstance(data__depth, (int, float, Decimal)) and not isinstance(data__depth, bool):
                if data__depth < 0:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".depth must be bigger than or equal to 0", value=data__depth, name="" + (name_prefix or "data") + ".depth", definition=None, rule='minimum')
        if data_keys:
            raise JsonSchemaValueException("" + (name_prefix or "data") + " must not contain "+str(data_keys)+" properties", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='additionalProperties')
    return data

def validate____defs_rostype(data, custom_formats={}, name_prefix=None):
    if not isinstance(data, (str)):
        raise JsonSchemaValueException("" + (name_prefix or "data") + " must be string", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='type')
    if isinstance(data, str):
        if not REGEX_PATTERNS['^[A-Za-z][A-Za-z0-9_]*/[A-Za-z][A-Za-z0-9_]*$'].search(data):
            raise JsonSchemaValueException("" + (name_prefix or "data") + " must match pattern ^[A-Za-z][A-Za-z0-9_]*/[A-Za-z][A-Za-z0-9_]*$", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='pattern')
    return data

def validate____defs_name(data, custom_formats={}, name_prefix=None):
    if not isinstance(data, (str)):
        raise JsonSchemaValueException("" + (name_prefix or "data") + " must be string", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='type')
    if isinstance(data, str):
        if not REGEX_PATTERNS['^[A-Za-z][A-Za-z0-9_]*$'].search(data):
            raise JsonSchemaValueException("" + (name_prefix or "data") + " must match pattern ^[A-Za-z][A-Za-z0-9_]*$", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='pattern')
    return data

from rosreconf.formats.schemamemo import remember_valid
validate____defs_interface = remember_valid(validate____defs_interface)
validate____defs_requirement = remember_valid(validate____defs_requirement)


VALIDATE = validate_urn_rosreconf_component_library_1
