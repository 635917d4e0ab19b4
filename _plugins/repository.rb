# frozen_string_literal: true

# Which repository the footer's "The course repository" and each page's "Edit this page"
# link to (_includes/footer.html, _includes/edit-link.html), decided when the site is
# built from _config.yml's `repository`:
#
# - `auto` (the default): the GitHub repository the clone being built came from, read
#   from `git remote` (`origin`, else the first remote), as owner/name. A clone with no
#   GitHub remote, or not a git clone at all, gets no such links: a local build never
#   links to a placeholder or to someone else's copy.
# - `none`: no such links.
# - `owner/name`: that repository (the Pages workflow passes the one it builds).
#
# `repository_branch: auto` is the branch checked out, else `main`. Afterwards
# site.repository is owner/name or "" (no links), and site.repository_branch a name.
require "open3"

module Sw2simSite
  module Repository
    OWNER_NAME = %r{\A[\w.-]+/[\w.-]+\z}.freeze
    # https://github.com/o/n(.git), git@github.com:o/n(.git), ssh://git@github.com/o/n
    GITHUB_REMOTE = %r{\A(?:https?://(?:[^@/]+@)?github\.com/|git@github\.com:|ssh://git@github\.com/)
                       ([\w.-]+/[\w.-]+?)(?:\.git)?/?\z}x.freeze
    DEFAULT_BRANCH = "main"

    module_function

    def resolve(config, source)
      chosen = config["repository"].to_s.strip
      config["repository"] = repository(chosen, source)
      branch = config["repository_branch"].to_s.strip
      config["repository_branch"] = branch.empty? || branch == "auto" ? current_branch(source) : branch
    end

    def repository(chosen, source)
      case chosen
      when "", "auto" then from_remote(source)
      when "none" then ""
      when OWNER_NAME then chosen
      else
        raise ArgumentError, "_config.yml: repository is #{chosen.inspect}; write owner/name " \
                             "(a GitHub repository), auto (read from git remote) or none (no links)"
      end
    end

    # owner/name of the clone's GitHub remote, or "".
    def from_remote(source)
      names = git(source, "remote").split
      name = names.include?("origin") ? "origin" : names.first
      return "" unless name

      url = git(source, "remote", "get-url", name).strip
      url[GITHUB_REMOTE, 1].to_s
    end

    def current_branch(source)
      branch = git(source, "symbolic-ref", "--quiet", "--short", "HEAD").strip
      branch.empty? ? DEFAULT_BRANCH : branch
    end

    # The command's output, or "" where git is missing or the folder is not a clone.
    def git(source, *args)
      output, _errors, status = Open3.capture3("git", "-C", source, *args)
      status.success? ? output : ""
    rescue SystemCallError
      ""
    end
  end
end

# Loaded by Jekyll; a test loads the module alone with Ruby.
if defined?(Jekyll::Hooks)
  Jekyll::Hooks.register :site, :after_init do |site|
    Sw2simSite::Repository.resolve(site.config, site.source)
  end
end
