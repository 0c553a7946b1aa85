# A minimal Open Job Description runner for the tests: reads a job template written by
# patina-farm (jobtemplate-2023-09), checks what a farm needs to move it (the job folder, the
# program and the plugin path as job parameters; no path of the machine that wrote it in a
# step's command or arguments), then runs its steps in dependency order with the given
# parameter values, each task of a step's INT range, the job environment's variables set.
#   python3 openjd_run.py TEMPLATE.yaml JobRoot=DIR [Name=VALUE ...]
import os
import re
import subprocess
import sys

import yaml


def main():
    template_path, assignments = sys.argv[1], sys.argv[2:]
    with open(template_path) as f:
        template = yaml.safe_load(f)
    if template.get("specificationVersion") != "jobtemplate-2023-09":
        sys.exit("not a jobtemplate-2023-09")
    definitions = {p["name"]: p for p in template.get("parameterDefinitions", [])}
    for name in ("JobRoot", "PatinaFarm", "PluginPath"):
        if name not in definitions:
            sys.exit(f"no job parameter {name}")
    if definitions["JobRoot"]["type"] != "PATH":
        sys.exit("JobRoot is not a PATH")
    params = {name: str(p.get("default", "")) for name, p in definitions.items()}
    for a in assignments:
        name, value = a.split("=", 1)
        params[name] = value
    default_root = str(definitions["JobRoot"]["default"])

    def expand(text, task=None):
        text = re.sub(r"\{\{Param\.(\w+)\}\}", lambda m: params[m.group(1)], str(text))
        if task is not None:
            text = text.replace("{{Task.Param.Task}}", str(task))
        return text

    env = dict(os.environ)
    for environment in template.get("jobEnvironments", []):
        for key, value in environment.get("variables", {}).items():
            env[key] = expand(value)
    steps = template["steps"]
    done = set()
    while len(done) < len(steps):
        for step in steps:
            needs = [d["dependsOn"] for d in step.get("dependencies", [])]
            if step["name"] in done or any(n not in done for n in needs):
                continue
            action = step["script"]["actions"]["onRun"]
            for part in [action["command"]] + action["args"]:
                if default_root in str(part):
                    sys.exit(f"step {step['name']} spells the job folder: {part}")
            tasks = [None]
            for p in step.get("parameterSpace", {}).get("taskParameterDefinitions", []):
                first, last = (int(x) for x in p["range"].split("-"))
                tasks = list(range(first, last + 1))
            for task in tasks:
                command = [expand(action["command"], task)] + [expand(a, task) for a in action["args"]]
                subprocess.run(command, env=env, check=True)
            done.add(step["name"])
    print("ran", ", ".join(s["name"] for s in steps), "with", params["JobRoot"])


main()
