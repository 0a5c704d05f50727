"""fastjsonschema's code for interoperability-schema.schema.json: written by
scripts/fast_validators.py, do not edit (see structure.fast_validator).
"""

# ruff: noqa
# fmt: off
# mypy: ignore-errors
SOURCE = 'fbf8e221978533803528e47fc24c60790dd4a80bace541cfea7c397898309a4d'
VERSION = "2.22.3"
from decimal import Decimal
import re
from fastjsonschema import JsonSchemaValueException, JsonSchemaValuesException


REGEX_PATTERNS = {
    '^/?[A-Za-z][A-Za-z0-9_]*(/[A-Za-z][A-Za-z0-9_]*)*$': re.compile('^/?[A-Za-z][A-Za-z0-9_]*(/[A-Za-z][A-Za-z0-9_]*)*\\Z'),
    '^[A-Za-z][A-Za-z0-9_]*$': re.compile('^[A-Za-z][A-Za-z0-9_]*\\Z')
}

NoneType = type(None)

def validate_urn_rosreconf_interoperability_schema_1(data, custom_formats={}, name_prefix=None):
    if not isinstance(data, (dict)):
        raise JsonSchemaValueException("" + (name_prefix or "data") + " must be object", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='type')
    data_is_dict = isinstance(data, dict)
    if data_is_dict:
        data__missing_keys = set(['format', 'version', 'name', 'skill', 'environment', 'roles']) - data.keys()
        if data__missing_keys:
            raise JsonSchemaValueException("" + (name_prefix or "data") + " must contain " + (str(sorted(data__missing_keys)) + " properties"), value=data, name="" + (name_prefix or "data") + "", definition=None, rule='required')
        data_keys = set(data.keys())
        if "format" in data_keys:
            data_keys.remove("format")
            data__format = data["format"]
            if not (isinstance(data__format, str) and data__format == 'rosreconf/interoperability-schema'):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".format must be same as const definition: rosreconf/interoperability-schema", value=data__format, name="" + (name_prefix or "data") + ".format", definition=None, rule='const')
        if "version" in data_keys:
            data_keys.remove("version")
            data__version = data["version"]
            if not (isinstance(data__version, (int, float)) and not isinstance(data__version, bool) and data__version == 1):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".version must be same as const definition: 1", value=data__version, name="" + (name_prefix or "data") + ".version", definition=None, rule='const')
        if "name" in data_keys:
            data_keys.remove("name")
            data__name = data["name"]
            validate____defs_name(data__name, custom_formats, (name_prefix or "data") + ".name")
        if "title" in data_keys:
            data_keys.remove("title")
            data__title = data["title"]
            if not isinstance(data__title, (str)):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".title must be string", value=data__title, name="" + (name_prefix or "data") + ".title", definition=None, rule='type')
        if "skill" in data_keys:
            data_keys.remove("skill")
            data__skill = data["skill"]
            if not isinstance(data__skill, (str)):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".skill must be string", value=data__skill, name="" + (name_prefix or "data") + ".skill", definition=None, rule='type')
        if "environment" in data_keys:
            data_keys.remove("environment")
            data__environment = data["environment"]
            if not isinstance(data__environment, (str)):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".environment must be string", value=data__environment, name="" + (name_prefix or "data") + ".environment", definition=None, rule='type')
        if "roles" in data_keys:
            data_keys.remove("roles")
            data__roles = data["roles"]
            if not isinstance(data__roles, (list, tuple)):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".roles must be array", value=data__roles, name="" + (name_prefix or "data") + ".roles", definition=None, rule='type')
            data__roles_is_list = isinstance(data__roles, (list, tuple))
            if data__roles_is_list:
                data__roles_len = len(data__roles)
                if data__roles_len < 1:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".roles must contain at least 1 items", value=data__roles, name="" + (name_prefix or "data") + ".roles", definition=None, rule='minItems')
                for data__roles_x, data__roles_item in enumerate(data__roles):
                    validate____defs_role(data__roles_item, custom_formats, (name_prefix or "data"))
        if "edges" in data_keys:
            data_keys.remove("edges")
            data__edges = data["edges"]
            if not isinstance(data__edges, (list, tuple)):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".edges must be array", value=data__edges, name="" + (name_prefix or "data") + ".edges", definition=None, rule='type')
            data__edges_is_list = isinstance(data__edges, (list, tuple))
            if data__edges_is_list:
                data__edges_len = len(data__edges)
                for data__edges_x, data__edges_item in enumerate(data__edges):
                    validate____defs_edge(data__edges_item, custom_formats, (name_prefix or "data"))
        if "nominal" in data_keys:
            data_keys.remove("nominal")
            data__nominal = data["nominal"]
            if not isinstance(data__nominal, (dict)):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".nominal must be object", value=data__nominal, name="" + (name_prefix or "data") + ".nominal", definition=None, rule='type')
            data__nominal_is_dict = isinstance(data__nominal, dict)
            if data__nominal_is_dict:
                data__nominal_keys = set(data__nominal.keys())
                for data__nominal_key in data__nominal_keys:
                    if data__nominal_key not in []:
                        data__nominal_value = data__nominal.get(data__nominal_key)
                        validate____defs_name(data__nominal_value, custom_formats, (name_prefix or "data"))
                data__nominal_len = len(data__nominal)
                if data__nominal_len != 0:
                    data__nominal_property_names = True
                    for data__nominal_key in data__nominal:
                        try:
                            validate____defs_name(data__nominal_key, custom_formats, (name_prefix or "data") + ".nominal")
                        except (JsonSchemaValueException, JsonSchemaValuesException):
                            data__nominal_property_names = False
                    if not data__nominal_property_names:
                        raise JsonSchemaValueException("" + (name_prefix or "data") + ".nominal must be named by propertyName definition", value=data__nominal, name="" + (name_prefix or "data") + ".nominal", definition=None, rule='propertyNames')
        if "simulation" in data_keys:
            data_keys.remove("simulation")
            data__simulation = data["simulation"]
            if not isinstance(data__simulation, (dict)):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".simulation must be object", value=data__simulation, name="" + (name_prefix or "data") + ".simulation", definition=None, rule='type')
            data__simulation_is_dict = isinstance(data__simulation, dict)
            if data__simulation_is_dict:
                data__simulation__missing_keys = set(['loops', 'duration']) - data__simulation.keys()
                if data__simulation__missing_keys:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".simulation must contain " + (str(sorted(data__simulation__missing_keys)) + " properties"), value=data__simulation, name="" + (name_prefix or "data") + ".simulation", definition=None, rule='required')
                data__simulation_keys = set(data__simulation.keys())
                if "loops" in data__simulation_keys:
                    data__simulation_keys.remove("loops")
                    data__simulation__loops = data__simulation["loops"]
                    if not isinstance(data__simulation__loops, (list, tuple)):
                        raise JsonSchemaValueException("" + (name_prefix or "data") + ".simulation.loops must be array", value=data__simulation__loops, name="" + (name_prefix or "data") + ".simulation.loops", definition=None, rule='type')
                    data__simulation__loops_is_list = isinstance(data__simulation__loops, (list, tuple))
                    if data__simulation__loops_is_list:
                        data__simulation__loops_len = len(data__simulation__loops)
                        if data__simulation__loops_len < 1:
                            raise JsonSchemaValueException("" + (name_prefix or "data") + ".simulation.loops must contain at least 1 items", value=data__simulation__loops, name="" + (name_prefix or "data") + ".simulation.loops", definition=None, rule='minItems')
                        for data__simulation__loops_x, data__simulation__loops_item in enumerate(data__simulation__loops):
                            validate____defs_loop(data__simulation__loops_item, custom_formats, (name_prefix or "data"))
                if "reference" in data__simulation_keys:
                    data__simulation_keys.remove("reference")
                    data__simulation__reference = data__simulation["reference"]
                    if not isinstance(data__simulation__reference, (int, float, Decimal)) or isinstance(data__simulation__reference, bool):
                        raise JsonSchemaValueException("" + (name_prefix or "data") + ".simulation.reference must be number", value=data__simulation__reference, name="" + (name_prefix or "data") + ".simulation.reference", definition=None, rule='type')
                    if isinstance(data__simulation__reference, (int, float, Decimal)) and not isinstance(data__simulation__reference, bool):
                        if data__simulation__reference <= 0:
                            raise JsonSchemaValueException("" + (name_prefix or "data") + ".simulation.reference must be bigger than 0", value=data__simulation__reference, name="" + (name_prefix or "data") + ".simulation.reference", definition=None, rule='exclusiveMinimum')
                if "duration" in data__simulation_keys:
                    data__simulation_keys.remove("duration")
                    data__simulation__duration = data__simulation["duration"]
                    if not isinstance(data__simulation__duration, (int, float, Decimal)) or isinstance(data__simulation__duration, bool):
                        raise JsonSchemaValueException("" + (name_prefix or "data") + ".simulation.duration must be number", value=data__simulation__duration, name="" + (name_prefix or "data") + ".simulation.duration", definition=None, rule='type')
                    if isinstance(data__simulation__duration, (int, float, Decimal)) and not isinstance(data__simulation__duration, bool):
                        if data__simulation__duration <= 0:
                            raise JsonSchemaValueException("" + (name_prefix or "data") + ".simulation.duration must be bigger than 0", value=data__simulation__duration, name="" + (name_prefix or "data") + ".simulation.duration", definition=None, rule='exclusiveMinimum')
                if "requirements" in data__simulation_keys:
                    data__simulation_keys.remove("requirements")
                    data__simulation__requirements = data__simulation["requirements"]
                    if not isinstance(data__simulation__requirements, (dict)):
                        raise JsonSchemaValueException("" + (name_prefix or "data") + ".simulation.requirements must be object", value=data__simulation__requirements, name="" + (name_prefix or "data") + ".simulation.requirements", definition=None, rule='type')
                    data__simulation__requirements_is_dict = isinstance(data__simulation__requirements, dict)
                    if data__simulation__requirements_is_dict:
                        data__simulation__requirements_keys = set(data__simulation__requirements.keys())
                        if "settling_time" in data__simulation__requirements_keys:
                            data__simulation__requirements_keys.remove("settling_time")
                            data__simulation__requirements__settlingtime = data__simulation__requirements["settling_time"]
                            if not isinstance(data__simulation__requirements__settlingtime, (int, float, Decimal)) or isinstance(data__simulation__requirements__settlingtime, bool):
                                raise JsonSchemaValueException("" + (name_prefix or "data") + ".simulation.requirements.settling_time must be number", value=data__simulation__requirements__settlingtime, name="" + (name_prefix or "data") + ".simulation.requirements.settling_time", definition=None, rule='type')
                            if isinstance(data__simulation__requirements__settlingtime, (int, float, Decimal)) and not isinstance(data__simulation__requirements__settlingtime, bool):
                                if data__simulation__requirements__settlingtime < 0:
                                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".simulation.requirements.settling_time must be bigger than or equal to 0", value=data__simulation__requirements__settlingtime, name="" + (name_prefix or "data") + ".simulation.requirements.settling_time", definition=None, rule='minimum')
                        if "steady_state_error" in data__simulation__requirements_keys:
                            data__simulation__requirements_keys.remove("steady_state_error")
                            data__simulation__requirements__steadystateerror = data__simulation__requirements["steady_state_error"]
                            if not isinstance(data__simulation__requirements__steadystateerror, (int, float, Decimal)) or isinstance(data__simulation__requirements__steadystateerror, bool):
                                raise JsonSchemaValueException("" + (name_prefix or "data") + ".simulation.requirements.steady_state_error must be number", value=data__simulation__requirements__steadystateerror, name="" + (name_prefix or "data") + ".simulation.requirements.steady_state_error", definition=None, rule='type')
                            if isinstance(data__simulation__requirements__steadystateerror, (int, float, Decimal)) and not isinstance(data__simulation__requirements__steadystateerror, bool):
                                if data__simulation__requirements__steadystateerror < 0:
                                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".simulation.requirements.steady_state_error must be bigger than or equal to 0", value=data__simulation__requirements__steadystateerror, name="" + (name_prefix or "data") + ".simulation.requirements.steady_state_error", definition=None, rule='minimum')
                        if "overshoot" in data__simulation__requirements_keys:
                            data__simulation__requirements_keys.remove("overshoot")
                            data__simulation__requirements__overshoot = data__simulation__requirements["overshoot"]
                            if not isinstance(data__simulation__requirements__overshoot, (int, float, Decimal)) or isinstance(data__simulation__requirements__overshoot, bool):
                                raise JsonSchemaValueException("" + (name_prefix or "data") + ".simulation.requirements.overshoot must be number", value=data__simulation__requirements__overshoot, name="" + (name_prefix or "data") + ".simulation.requirements.overshoot", definition=None, rule='type')
                            if isinstance(data__simulation__requirements__overshoot, (int, float, Decimal)) and not isinstance(data__simulation__requirements__overshoot, bool):
                                if data__simulation__requirements__overshoot < 0:
                                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".simulation.requirements.overshoot must be bigger than or equal to 0", value=data__simulation__requirements__overshoot, name="" + (name_prefix or "data") + ".simulation.requirements.overshoot", definition=None, rule='minimum')
                        if data__simulation__requirements_keys:
                            raise JsonSchemaValueException("" + (name_prefix or "data") + ".simulation.requirements must not contain "+str(data__simulation__requirements_keys)+" properties", value=data__simulation__requirements, name="" + (name_prefix or "data") + ".simulation.requirements", definition=None, rule='additionalProperties')
                if data__simulation_keys:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".simulation must not contain "+str(data__simulation_keys)+" properties", value=data__simulation, name="" + (name_prefix or "data") + ".simulation", definition=None, rule='additionalProperties')
        if data_keys:
            raise JsonSchemaValueException("" + (name_prefix or "data") + " must not contain "+str(data_keys)+" properties", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='additionalProperties')
    return data

def validate____defs_loop(data, custom_formats={}, name_prefix=None):
    if not isinstance(data, (dict)):
        raise JsonSchemaValueException("" + (name_prefix or "data") + " must be object", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='type')
    data_is_dict = isinstance(data, dict)
    if data_is_dict:
        data__missing_keys = set(['name', 'forward', 'plant']) - data.keys()
        if data__missing_keys:
            raise JsonSchemaValueException("" + (name_prefix or "data") + " must contain " + (str(sorted(data__missing_keys)) + " properties"), value=data, name="" + (name_prefix or "data") + "", definition=None, rule='required')
        data_keys = set(data.keys())
        if "name" in data_keys:
            data_keys.remove("name")
            data__name = data["name"]
            validate____defs_name(data__name, custom_formats, (name_prefix or "data") + ".name")
        if "forward" in data_keys:
            data_keys.remove("forward")
            data__forward = data["forward"]
            if not isinstance(data__forward, (list, tuple)):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".forward must be array", value=data__forward, name="" + (name_prefix or "data") + ".forward", definition=None, rule='type')
            data__forward_is_list = isinstance(data__forward, (list, tuple))
            if data__forward_is_list:
                data__forward_len = len(data__forward)
                if data__forward_len < 1:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".forward must contain at least 1 items", value=data__forward, name="" + (name_prefix or "data") + ".forward", definition=None, rule='minItems')
                def fn(var): return frozenset(dict((k, fn(v)) for k, v in var.items()).items()) if hasattr(var, "items") else tuple(fn(v) for v in var) if isinstance(var, (dict, list)) else (bool, var) if isinstance(var, bool) else var
                if data__forward_len > len(set(fn(data__forward_x) for data__forward_x in data__forward)):
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".forward must contain unique items", value=data__forward, name="" + (name_prefix or "data") + ".forward", definition=None, rule='uniqueItems')
                for data__forward_x, data__forward_item in enumerate(data__forward):
                    validate____defs_name(data__forward_item, custom_formats, (name_prefix or "data"))
        if "plant" in data_keys:
            data_keys.remove("plant")
            data__plant = data["plant"]
            validate____defs_dynamics(data__plant, custom_formats, (name_prefix or "data") + ".plant")
        if "feedback" in data_keys:
            data_keys.remove("feedback")
            data__feedback = data["feedback"]
            if not isinstance(data__feedback, (list, tuple)):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".feedback must be array", value=data__feedback, name="" + (name_prefix or "data") + ".feedback", definition=None, rule='type')
            data__feedback_is_list = isinstance(data__feedback, (list, tuple))
            if data__feedback_is_list:
                def fn(var): return frozenset(dict((k, fn(v)) for k, v in var.items()).items()) if hasattr(var, "items") else tuple(fn(v) for v in var) if isinstance(var, (dict, list)) else (bool, var) if isinstance(var, bool) else var
                data__feedback_len = len(data__feedback)
                if data__feedback_len > len(set(fn(data__feedback_x) for data__feedback_x in data__feedback)):
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".feedback must contain unique items", value=data__feedback, name="" + (name_prefix or "data") + ".feedback", definition=None, rule='uniqueItems')
                for data__feedback_x, data__feedback_item in enumerate(data__feedback):
                    validate____defs_name(data__feedback_item, custom_formats, (name_prefix or "data"))
        if data_keys:
            raise JsonSchemaValueException("" + (name_prefix or "data") + " must not contain "+str(data_keys)+" properties", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='additionalProperties')
    return data

def validate____defs_dynamics(data, custom_formats={}, name_prefix=None):
    if not isinstance(data, (dict)):
        raise JsonSchemaValueException("" + (name_prefix or "data") + " must be object", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='type')
    data_any_of_count1 = 0
    if not data_any_of_count1:
        try:
            data_is_dict = isinstance(data, dict)
            if data_is_dict:
                data__missing_keys = set(['transfer_function']) - data.keys()
                if data__missing_keys:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + " must contain " + (str(sorted(data__missing_keys)) + " properties"), value=data, name="" + (name_prefix or "data") + "", definition=None, rule='required')
            data_any_of_count1 += 1
        except (JsonSchemaValueException, JsonSchemaValuesException): pass
    if not data_any_of_count1:
        try:
            data_is_dict = isinstance(data, dict)
            if data_is_dict:
                data__missing_keys = set(['state_space']) - data.keys()
                if data__missing_keys:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + " must contain " + (str(sorted(data__missing_keys)) + " properties"), value=data, name="" + (name_prefix or "data") + "", definition=None, rule='required')
            data_any_of_count1 += 1
        except (JsonSchemaValueException, JsonSchemaValuesException): pass
    if not data_any_of_count1:
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

def validate____defs_edge(data, custom_formats={}, name_prefix=None):
    if not isinstance(data, (dict)):
        raise JsonSchemaValueException("" + (name_prefix or "data") + " must be object", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='type')
    data_is_dict = isinstance(data, dict)
    if data_is_dict:
        data__missing_keys = set(['consumer', 'providers']) - data.keys()
        if data__missing_keys:
            raise JsonSchemaValueException("" + (name_prefix or "data") + " must contain " + (str(sorted(data__missing_keys)) + " properties"), value=data, name="" + (name_prefix or "data") + "", definition=None, rule='required')
        data_keys = set(data.keys())
        if "consumer" in data_keys:
            data_keys.remove("consumer")
            data__consumer = data["consumer"]
            validate____defs_name(data__consumer, custom_formats, (name_prefix or "data") + ".consumer")
        if "providers" in data_keys:
            data_keys.remove("providers")
            data__providers = data["providers"]
            if not isinstance(data__providers, (list, tuple)):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".providers must be array", value=data__providers, name="" + (name_prefix or "data") + ".providers", definition=None, rule='type')
            data__providers_is_list = isinstance(data__providers, (list, tuple))
            if data__providers_is_list:
                data__providers_len = len(data__providers)
                if data__providers_len < 1:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".providers must contain at least 1 items", value=data__providers, name="" + (name_prefix or "data") + ".providers", definition=None, rule='minItems')
                def fn(var): return frozenset(dict((k, fn(v)) for k, v in var.items()).items()) if hasattr(var, "items") else tuple(fn(v) for v in var) if isinstance(var, (dict, list)) else (bool, var) if isinstance(var, bool) else var
                if data__providers_len > len(set(fn(data__providers_x) for data__providers_x in data__providers)):
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".providers must contain unique items", value=data__providers, name="" + (name_prefix or "data") + ".providers", definition=None, rule='uniqueItems')
                for data__providers_x, data__providers_item in enumerate(data__providers):
                    validate____defs_name(data__providers_item, custom_formats, (name_prefix or "data"))
        if "interfaces" in data_keys:
            data_keys.remove("interfaces")
            data__interfaces = data["interfaces"]
            if not isinstance(data__interfaces, (list, tuple)):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".interfaces must be array", value=data__interfaces, name="" + (name_prefix or "data") + ".interfaces", definition=None, rule='type')
            data__interfaces_is_list = isinstance(data__interfaces, (list, tuple))
            if data__interfaces_is_list:
                data__interfaces_len = len(data__interfaces)
                if data__interfaces_len < 1:
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".interfaces must contain at least 1 items", value=data__interfaces, name="" + (name_prefix or "data") + ".interfaces", definition=None, rule='minItems')
                def fn(var): return frozenset(dict((k, fn(v)) for k, v in var.items()).items()) if hasattr(var, "items") else tuple(fn(v) for v in var) if isinstance(var, (dict, list)) else (bool, var) if isinstance(var, bool) else var
                if data__interfaces_len > len(set(fn(data__interfaces_x) for data__interfaces_x in data__interfaces)):
                    raise JsonSchemaValueException("" + (name_prefix or "data") + ".interfaces must contain unique items", value=data__interfaces, name="" + (name_prefix or "data") + ".interfaces", definition=None, rule='uniqueItems')
                for data__interfaces_x, data__interfaces_item in enumerate(data__interfaces):
                    validate____defs_label(data__interfaces_item, custom_formats, (name_prefix or "data"))
        if "optional" in data_keys:
            data_keys.remove("optional")
            data__optional = data["optional"]
            if not isinstance(data__optional, (bool)):
                raise JsonSchemaValueException("" + (name_prefix or "data") + ".optional must be boolean", value=data__optional, name="" + (name_prefix or "data") + ".optional", definition=None, rule='type')
        if data_keys:
            raise JsonSchemaValueException("" + (name_prefix or "data") + " must not contain "+str(data_keys)+" properties", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='additionalProperties')
    return data

def validate____defs_label(data, custom_formats={}, name_prefix=None):
    if not isinstance(data, (str)):
        raise JsonSchemaValueException("" + (name_prefix or "data") + " must be string", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='type')
    if isinstance(data, str):
        if not REGEX_PATTERNS['^/?[A-Za-z][A-Za-z0-9_]*(/[A-Za-z][A-Za-z0-9_]*)*$'].search(data):
            raise JsonSchemaValueException("" + (name_prefix or "data") + " must match pattern ^/?[A-Za-z][A-Za-z0-9_]*(/[A-Za-z][A-Za-z0-9_]*)*$", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='pattern')
    return data

def validate____defs_role(data, custom_formats={}, name_prefix=None):
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
        if data_keys:
            raise JsonSchemaValueException("" + (name_prefix or "data") + " must not contain "+str(data_keys)+" properties", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='additionalProperties')
    return data

def validate____defs_name(data, custom_formats={}, name_prefix=None):
    if not isinstance(data, (str)):
        raise JsonSchemaValueException("" + (name_prefix or "data") + " must be string", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='type')
    if isinstance(data, str):
        if not REGEX_PATTERNS['^[A-Za-z][A-Za-z0-9_]*$'].search(data):
            raise JsonSchemaValueException("" + (name_prefix or "data") + " must match pattern ^[A-Za-z][A-Za-z0-9_]*$", value=data, name="" + (name_prefix or "data") + "", definition=None, rule='pattern')
    return data


VALIDATE = validate_urn_rosreconf_interoperability_schema_1
